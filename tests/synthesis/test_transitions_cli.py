"""Test ``python -m synthesis.transitions``: simulate, build, evaluate (CSV, LaTeX, PNG), speed."""

import csv
import subprocess
import sys

from synthesis.transitions.cli import main
from synthesis.transitions.evaluate import PUBLISHED_INPUT


def test_simulate_build_evaluate_end_to_end(tmp_path, capsys):
    assert (
        main(["simulate", "--out", str(tmp_path / "cap"), "--signers", "2", "--sentences", "2"])
        == 0
    )
    recordings = sorted((tmp_path / "cap").glob("*.bvh"))
    assert len(recordings) == 4
    assert main(["build", *map(str, recordings), "--out", str(tmp_path / "db.json")]) == 0
    assert "(simulated captures)" in capsys.readouterr().out
    assert main(["evaluate", str(tmp_path / "db.json"), "--out", str(tmp_path / "eval")]) == 0
    out = capsys.readouterr().out
    assert out.splitlines()[0].startswith("model\tshoulder x")
    assert "best search for the data-driven Hermite:" in out and "simulated captures" in out
    for name in (
        "table.csv",
        "table.tex",
        "transitions.csv",
        "weightings.csv",
        "rmse.png",
        "verdict.txt",
    ):
        assert (tmp_path / "eval" / name).stat().st_size > 0, name
    assert len(list((tmp_path / "eval").glob("curves-*.png"))) == 3
    with (tmp_path / "eval" / "table.csv").open() as handle:
        rows = list(csv.DictReader(handle))
    assert [r["model"] for r in rows] == [
        "linear",
        "simple Hermite",
        "Hermite (data-driven)",
        "B-spline (data-driven)",
    ]
    assert "simulated captures" in (tmp_path / "eval" / "table.tex").read_text()
    # Issue 38: our figures and the published ones, each saying what it was computed on.
    assert {r["input"] for r in rows} == {
        f"{rows[0]['transitions']} transitions from simulated captures"
    }
    assert [r["published_best_in"] for r in rows] == ["7", "57", "17", "7"]
    assert {r["published_input"] for r in rows} == {PUBLISHED_INPUT}
    assert PUBLISHED_INPUT in (tmp_path / "eval" / "table.tex").read_text()


def test_bad_input_exits_2_with_the_reason(tmp_path, capsys):
    (tmp_path / "a.bvh").write_text("not a bvh")
    assert main(["build", str(tmp_path / "a.bvh"), "--out", str(tmp_path / "db.json")]) == 2
    assert "no segmentation beside it" in capsys.readouterr().err
    (tmp_path / "db.json").write_text("{}")
    assert main(["evaluate", str(tmp_path / "db.json"), "--out", str(tmp_path / "e")]) == 2
    assert "not a transition database" in capsys.readouterr().err


def test_module_runs_and_plots_speed(tmp_path):
    result = subprocess.run(
        [
            sys.executable,
            "-m",
            "synthesis.transitions",
            "speed",
            "BUT MY NEW",
            "--out",
            str(tmp_path / "speed.png"),
            "--models",
            "keyed,blended",
        ],
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert result.returncode == 0, result.stderr
    assert (tmp_path / "speed.png").stat().st_size > 1000


def test_lexicon_commands_write_manifests(tmp_path, capsys):
    assert main(["lexicon", "--simulate", "WHERE", "SURPRISE", "--out", str(tmp_path)]) == 0
    assert "2 simulated recorded signs" in capsys.readouterr().out
    recordings = sorted(map(str, tmp_path.glob("*.bvh")))
    assert main(["lexicon", *recordings, "--out", str(tmp_path / "mine.json")]) == 0
    from synthesis.transitions.lexicon import read_lexicon

    assert set(read_lexicon(tmp_path / "mine.json").signs) == {"WHERE", "SURPRISE"}
    assert main(["lexicon", str(tmp_path / "nothing.txt"), "--out", str(tmp_path / "x.json")]) == 2
    assert "a .bvh or a .pose file" in capsys.readouterr().err
