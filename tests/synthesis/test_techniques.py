"""Test the technique registry: declarations drive validation, the CLI, the hash, the motion."""

import json
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from stimuli import ClipSpec
from synthesis.cli import main, parser
from synthesis.techniques import (
    MOTION,
    REGISTRY,
    ClipError,
    ClipRequest,
    Parameter,
    Technique,
    build_motion,
    validate_parameters,
)

ROOT = Path(__file__).resolve().parents[2]


def _slow_down(build):
    """Repeat every frame ``slowdown`` times (a toy technique for these tests)."""
    factor = build.request.parameters["slowdown"]
    return build.but(motion=np.repeat(build.motion, factor, axis=0))


TOY = Technique(
    name="toy",
    label="Toy slow motion",
    kinds=frozenset({"word"}),
    parameters=(
        Parameter("slowdown", "int", 1, "Show every frame this many times.", minimum=1, maximum=4),
    ),
    source="a test",
    stage=MOTION,
    apply=_slow_down,
)


def test_a_registered_toy_technique_is_validated_offered_hashed_and_applied(capsys):
    plain = ClipSpec("word", "AB", {"timing": "constant"})
    with REGISTRY.registered(TOY):
        request = ClipRequest("word", "AB", {"timing": "constant", "slowdown": 2})
        assert request.parameters["slowdown"] == 2
        with pytest.raises(ClipError, match="slowdown must be at most 4"):
            ClipRequest("word", "AB", {"slowdown": 9})
        with pytest.raises(ClipError, match=r"'slowdown' \(Toy slow motion\) does not apply"):
            ClipRequest("sentence", "ME GET", {"slowdown": 2})
        assert "--slowdown" in parser()._subparsers._group_actions[0].choices["spell"].format_help()
        assert "toy" in parser().format_help()
        hashed = ClipSpec("word", "AB", {"timing": "constant"})
        assert hashed.parameters["slowdown"] == 1 and hashed.content_hash() != plain.content_hash()
        slow = build_motion(request).motion
        assert (
            main(["spell", "AB", "--condition", "constant", "--slowdown", "3", "--timing-only"])
            == 0
        )
        capsys.readouterr()
    normal = build_motion(ClipRequest("word", "AB", {"timing": "constant"})).motion
    assert len(slow) == 2 * len(normal)
    np.testing.assert_array_equal(slow[::2], normal)
    assert "slowdown" not in ClipRequest("word", "AB").parameters  # unregistered again
    assert "toy" not in parser().format_help()


@pytest.mark.parametrize(
    ("kind", "parameters", "message"),
    [
        ("sentence", {"spin": False}, "Unknown parameter 'spin' for a sentence"),
        ("sentence", {"spine": "no"}, "spine must be true or false, not 'no'"),
        ("word", {"hold_ms": True}, "hold_ms must be a number, not True"),
        ("word", {"hold_ms": float("nan")}, "hold_ms must be a finite number"),
        (
            "word",
            {"spine": False},
            r"'spine' \(Automated spine motion\) does not apply to a "
            "fingerspelled word",
        ),
        ("poem", {}, "Unknown item kind 'poem'"),
        ("word", {"timing": "mocap"}, "timing 'mocap' plays a performance"),
        ("word", {"source": "recording"}, "source 'recording' needs the recording"),
        ("sentence", {"view": "hand"}, "renders in the upper-body view"),
        ("word", {"rate_hz": 0}, "rate_hz must be at least 1 Hz"),
    ],
)
def test_bad_parameters_are_refused_naming_them(kind, parameters, message):
    with pytest.raises(ClipError, match=message):
        validate_parameters(kind, parameters)


def test_validation_returns_only_what_was_given_checked():
    assert validate_parameters("sentence", {"spine": False, "rate_hz": 30}) == {
        "spine": False,
        "rate_hz": 30.0,
    }


def test_a_request_round_trips_and_defaults_name_the_same_clip():
    short = ClipRequest.from_parameters("word", "DAVID", {"timing": "variable", "seed": 4})
    assert ClipRequest(**short.to_dict()) == short
    spelled_out = ClipRequest("word", "DAVID", dict(short.parameters), seed=4)
    assert spelled_out == short
    assert (
        ClipSpec.from_request(short).content_hash()
        == ClipSpec.from_request(spelled_out).content_hash()
    )


def test_a_file_parameter_counts_by_its_content(tmp_path):
    from synthesis.timing import WordTiming

    saved = tmp_path / "ok.json"
    saved.write_text(json.dumps(WordTiming(("O", "K"), (100, 100), (100,), "mine").to_dict()))
    spec = ClipSpec("word", "OK", {"timing_file": str(saved)})
    before = spec.content_hash()
    saved.write_text(json.dumps(WordTiming(("O", "K"), (200, 100), (100,), "mine").to_dict()))
    assert spec.content_hash() != before


def test_the_schema_lists_every_parameter_and_refuses_others():
    schema = REGISTRY.schema()
    assert set(schema) == {"word", "sentence", "sign_pair"}
    assert schema["sign_pair"]["properties"] == schema["sentence"]["properties"]
    assert schema["word"]["additionalProperties"] is False
    assert schema["word"]["properties"]["timing"]["enum"] == [
        "mocap",
        "variable",
        "constant",
        "normalized",
        "simple",
    ]
    assert schema["sentence"]["properties"]["spine"]["type"] == "boolean"


def test_techniques_describe_a_condition_in_plain_words():
    lines = REGISTRY.describe("word", {"timing": "constant", "hold_ms": 200, "source": "simulated"})
    assert lines == [
        "Performance: a simulated capture",
        "Timing model: Constant (200 ms holds, the last 800 ms, 250 ms transitions)",
        "Hand DOFs: full hand",
        "Avatar: human signer (woman, medium skin)",
    ]
    assert REGISTRY.describe("sentence", {"spine": False})[1] == "Automated spine motion: off"
    assert REGISTRY.describe("word", {"avatar": "simple"})[-1] == "Avatar: simple avatar"


def test_the_cli_lists_the_techniques(capsys):
    result = subprocess.run(
        [sys.executable, "-m", "synthesis", "--help"],
        cwd=ROOT,
        capture_output=True,
        text=True,
        check=True,
    )
    for technique in REGISTRY.techniques:
        assert technique.label in result.stdout
    assert main(["techniques", "--json"]) == 0
    assert json.loads(capsys.readouterr().out) == REGISTRY.schema()


def test_the_timing_names_are_listed_in_one_place():
    from synthesis.techniques.timing import TIMINGS
    from synthesis.timing.recordings import MODEL_TIMINGS

    result = subprocess.run(
        [
            "grep",
            "-rlnE",
            "--exclude-dir=migrations",
            '"(mocap|variable)", "(variable|constant)"',
            "synthesis",
            "stimuli",
            "studyplatform",
        ],
        cwd=ROOT,
        capture_output=True,
        text=True,
    )
    assert result.stdout.split() == ["synthesis/timing/recordings.py"]
    assert TIMINGS[1:-1] == MODEL_TIMINGS and (TIMINGS[0], TIMINGS[-1]) == ("mocap", "simple")


def test_a_clip_hash_changes_with_the_files_a_clip_comes_from_and_no_others(tmp_path):
    """A change to the kinematics renames every clip; one to a command line, a report or
    the stimulus check does not (issue 57: upgrading for a fix in a report re-rendered
    every clip and locked open studies), though the disk cache's key still changes."""
    copy = tmp_path / "synthesis"
    shutil.copytree(ROOT / "synthesis", copy, ignore=shutil.ignore_patterns("__pycache__"))
    code = (
        "from synthesis.identity import code_digest, engine_digest\n"
        "from stimuli import ClipSpec\n"
        "print(engine_digest(), ClipSpec('word', 'AB').content_hash(), code_digest())\n"
    )

    def digests() -> list[str]:
        env = {"PYTHONPATH": f"{tmp_path}:{ROOT}", "PATH": "/usr/bin:/bin"}
        result = subprocess.run(
            [sys.executable, "-c", code],
            cwd=tmp_path,
            env=env,
            capture_output=True,
            text=True,
            check=True,
        )
        return result.stdout.split()

    def change(path) -> None:
        path.write_text(path.read_text() + "\nCHANGED = 1\n")

    before = digests()
    # Layout, comments and docstrings cannot change a pixel: no digest changes.
    kinematics = copy / "skeleton" / "kinematics.py"
    source = kinematics.read_text()
    kinematics.write_text(
        source.replace('"""', '"""Reworded. ', 1).replace("\n\n", "\n\n\n") + "# a comment\n"
    )
    assert digests() == before
    # Nor can types: a type hint changed, a typing import and a TYPE_CHECKING block added.
    kinematics.write_text(
        source.replace(
            "def forward_kinematics(motion: Motion) -> Pose:",
            "def forward_kinematics(motion: 'Motion | None') -> 'Pose':",
        )
        + "\nfrom typing import TYPE_CHECKING\nif TYPE_CHECKING:\n    import pandas\n"
        + "LIMIT: float = 1.0\n"
    )
    typed = digests()
    kinematics.write_text(source + "\nLIMIT: int = 1.0\n")
    assert digests() == typed
    kinematics.write_text(source + "\nLIMIT: int = 2.0\n")  # a value is code
    assert digests()[0] != typed[0]
    # A module a render-path file names for its types only is not on the render path.
    kinematics.write_text(
        source
        + "\nfrom typing import TYPE_CHECKING\nif TYPE_CHECKING:\n    from synthesis import cli\n"
    )
    assert digests() == before
    for outside in ("cli.py", "transitions/report.py", "quality/speed.py", "timing/learning.py"):
        change(copy / outside)
        now = digests()
        assert now[:2] == before[:2] and now[2] != before[2], outside
        before = now
    change(copy / "skeleton" / "kinematics.py")
    after = digests()
    assert before[0] != after[0] and before[1] != after[1]


@pytest.mark.parametrize(
    ("argv", "named"),
    [
        (["spell", "AB", "--spine", "off"], "unrecognized arguments: --spine"),
        (["sentence", "ME GET", "--timing", "constant"], "unrecognized arguments: --timing"),
        (["spell", "AB", "--timing", "fast"], "argument --timing: invalid choice: 'fast'"),
        (["spell", "AB", "--hold-ms", "long"], "argument --hold-ms: invalid float value"),
        (["sentence", "ME GET", "--spine", "maybe"], "argument --spine: use on or off"),
    ],
)
def test_the_cli_refuses_bad_technique_flags_naming_them(argv, named, capsys):
    with pytest.raises(SystemExit) as raised:
        main(argv)
    assert raised.value.code == 2 and named in capsys.readouterr().err


def test_the_cli_refuses_a_bad_value_the_registry_checks(capsys):
    assert main(["spell", "AB", "--hold-ms", "0", "--timing-only"]) == 2
    assert "hold_ms must be at least 1 ms" in capsys.readouterr().err
