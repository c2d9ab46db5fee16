"""Run every command of docs/reproducing.md on a small input.

The guide's commands are read from its ``sh`` blocks; each runs in-process in a
directory holding the inputs it names, made here: hand captures (the engine's spelling
written as BVH), annotated holds and transitions, recordings of spelled words, and the
golden test's small tidy CSV as study responses. Options that make a command long
(database sizes, seconds of simulated gestures, sentences) are shrunk for the test, and
the output each command promises is checked. A command added to the guide without a
small input here fails the test.
"""

import glob
import re
import shlex
import shutil
from pathlib import Path

import numpy as np
import pytest

GUIDE = Path(__file__).resolve().parents[1] / "docs" / "reproducing.md"
SMALL_STUDY = Path(__file__).parent / "analysis" / "reference" / "small_study.csv"
PAPER_SMALL = ["--poses", "50", "--sizes", "2"]
GESTURES_SMALL = ["--paper-input", "gestures", "--gesture-seconds", "9"]
# Per command (its first words), what is swapped or added to make it small, and a file
# it must write.
SMALL = {
    "synthesis.hands reduce capture.bvh": ([], [], "reduction/steps.tex"),
    "synthesis.hands reduce --spell": ([], [], "reduction-engine/steps.csv"),
    "synthesis.hands reduce --human-letters": (
        [("ABCDEFGHIJKLMNOPQRSTUVWXYZ", "ABC")],
        [],
        "reduction-human/steps.csv",
    ),
    "synthesis.hands database": ([], [], "poses.npz"),
    "synthesis.hands markers --configuration paper": ([], PAPER_SMALL, "table-3-1/table-3-1.tex"),
    "synthesis.hands reconstruct": ([], [], "lwr/errors-by-markers.tex"),
    "synthesis.hands markers --configuration both": (
        [],
        [*PAPER_SMALL, *GESTURES_SMALL, "--words", "CAT", "--no-compare"],
        "table-3-1-ours/table-3-1.csv",
    ),
    "synthesis.timing train --holds": ([], [], "model.json"),
    "synthesis.timing train take-david.bvh": ([], [], "model.json"),
    "synthesis.timing compare": ([], [], None),
    "synthesis.timing metrics": ([], [], "fig-4-7/metrics.tex"),
    "synthesis.timing evaluate": ([], [], "leave-one-out/leave-one-out.csv"),
    "synthesis.timing curves": ([], ["--repeats", "2"], "fig-4-4/curves.csv"),
    "synthesis.transitions build sentences": ([], [], "db.json"),
    "synthesis.transitions evaluate db.json": ([], [], "table-5-1/table.tex"),
    "synthesis.transitions simulate": (
        [("--signers 4", "--signers 2"), ("--sentences 6", "--sentences 1")],
        [],
        "simulated",
    ),
    "synthesis.transitions build simulated": ([], [], "simulated.json"),
    "synthesis.transitions evaluate simulated.json": ([], [], "table-5-1-simulated/verdict.txt"),
    "synthesis.transitions speed": ([], [], "speed.png"),
    "analysis report responses.csv --out report/": ([], [], "report/report.html"),
    "analysis report responses.csv --out report-fingerspelling/": (
        [],
        [],
        "report-fingerspelling/report.html",
    ),
}


def guide_commands() -> list[str]:
    """Return the guide's commands: the ``python -m`` lines of its ``sh`` blocks, in order."""
    blocks = re.findall(r"```sh\n(.*?)```", GUIDE.read_text("utf-8"), re.S)
    return [line.strip() for block in blocks for line in block.splitlines() if line.strip()]


def _main(module: str):
    if module == "analysis":
        from analysis.cli import main
    elif module == "synthesis.hands":
        from synthesis.hands.cli import main
    elif module == "synthesis.timing":
        from synthesis.timing.cli import main
    elif module == "synthesis.transitions":
        from synthesis.transitions.cli import main
    else:
        raise AssertionError(f"The guide runs {module}, which this test does not know.")
    return main


def _write_hand(path: Path, words: list[str], rate_hz: float) -> None:
    from synthesis.fingerspelling.spelling import spell
    from synthesis.rigs.hand import HandModel
    from synthesis.skeleton.bvh import write_bvh
    from synthesis.skeleton.motion import Motion

    model = HandModel()
    dofs = np.vstack([spell(word, rate_hz=rate_hz, timing=None, lead_ms=300) for word in words])
    write_bvh(Motion(model.skeleton, model.channel_values(dofs), 1 / rate_hz), path)


@pytest.fixture(scope="module")
def inputs(tmp_path_factory) -> Path:
    from synthesis.transitions.cli import main as transitions

    here = tmp_path_factory.mktemp("reproducing")
    _write_hand(here / "capture.bvh", ["HEAVEN", "GIRL"], 120.0)
    _write_hand(here / "selection.bvh", ["WALK"], 120.0)
    _write_hand(here / "test.bvh", ["CAT"], 120.0)
    _write_hand(here / "take-david.bvh", ["DAVID"], 60.0)
    _write_hand(here / "take-victor.bvh", ["VICTOR"], 60.0)
    holds = ["word,index,hold_ms"] + [
        f"{w},{k},{h}"
        for w, hs in (("CAT", (300, 200, 350)), ("DOG", (280, 210, 330)))
        for k, h in enumerate(hs)
    ]
    (here / "holds.csv").write_text("\n".join(holds) + "\n")
    (here / "transitions.csv").write_text(
        "word,index,transition_ms\nCAT,0,200\nCAT,1,180\nDOG,0,230\nDOG,1,190\n"
    )
    argv = ["simulate", "--signers", "2", "--sentences", "1", "--seed", "4"]
    assert transitions([*argv, "--out", str(here / "sentences")]) == 0
    shutil.copy(SMALL_STUDY, here / "responses.csv")
    return here


def _small(command: str) -> tuple[str, list[str], str | None]:
    """Return the command's small form (module and arguments) and the file it writes."""
    assert command.startswith("python -m "), command
    words = command.removeprefix("python -m ")
    matches = [key for key in SMALL if words.startswith(key)]
    assert len(matches) == 1, f"No (or more than one) small input for: {command}"
    swaps, extra, output = SMALL[matches[0]]
    for old, new in swaps:
        assert old in words, f"{command}: expected {old!r} to shrink"
        words = words.replace(old, new)
    return words, extra, output


def test_the_guide_names_every_seed_and_a_small_input_for_every_command():
    text = GUIDE.read_text("utf-8")
    for seed in (
        "Seed 000 ch. 3",
        "Seed 000 ch. 4",
        "Seed 000 ch. 5",
        "Seed 001",
        "Seed 002",
        "Seed 003",
        "Seed 004",
    ):
        assert f"## {seed}" in text
    commands = guide_commands()
    assert len(commands) >= 15
    covered = {
        key for c in commands for key in SMALL if c.removeprefix("python -m ").startswith(key)
    }
    assert covered == set(SMALL), f"Not in the guide any more: {set(SMALL) - covered}"


def test_every_command_of_the_guide_runs_in_order(inputs, monkeypatch, capsys):
    """One test, in the guide's order: later commands read what earlier ones wrote."""
    monkeypatch.chdir(inputs)
    for command in guide_commands():
        words, extra, output = _small(command)
        parts = shlex.split(words)
        argv = [item for part in parts[1:] for item in (sorted(glob.glob(part)) or [part])]
        status = _main(parts[0])([*argv, *extra])
        printed = capsys.readouterr()
        assert status == 0, f"{command}: {printed.err}"
        if output is not None:
            assert (inputs / output).exists(), f"{command} did not write {output}"
        if any(
            word in words
            for word in ("reduce", "markers", "reconstruct", "train", "timing evaluate")
        ):
            assert "published" in printed.out or "seed 000" in printed.out, command
    verdict = (inputs / "table-5-1" / "verdict.txt").read_text()
    assert "(seed 001: 63.6 %)" in verdict and "(seed 001: 12.5 %)" in verdict
    curves = (inputs / "fig-4-4" / "curves.csv").read_text()
    assert "72.37" in curves and "simulated" in curves
    table = (inputs / "table-3-1" / "table-3-1.csv").read_text()
    assert "recordings capture.bvh; markers chosen on selection.bvh, tested on test.bvh" in table
