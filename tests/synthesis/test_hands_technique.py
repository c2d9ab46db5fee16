"""Test the reduced hand as a technique and ``python -m synthesis.hands reduce`` (spec 05)."""

import csv

import numpy as np
import pytest

from synthesis.hands.cli import main
from synthesis.hands.motion import digit_columns, read_hand_motion
from synthesis.rigs.body import BodyModel
from synthesis.rigs.hand import HandModel
from synthesis.techniques import ClipRequest, build_motion


def test_digit_curves_carry_seed_002_names():
    columns, names = digit_columns(BodyModel("right"))
    assert len(columns) == 50 and names[0] == "riThumbCMCx" and "leRingMCPy" in names
    columns, names = digit_columns(HandModel("left"))
    assert len(columns) == 25 and names[-1] == "lePinkyDIPy"


def test_a_reduced_hand_changes_only_the_digits_it_reduces():
    full = build_motion(ClipRequest("word", "ELEPHANT")).motion
    reduced = build_motion(ClipRequest("word", "ELEPHANT", {"hand": "reduced"})).motion
    columns, _ = digit_columns(HandModel("right"))
    others = np.setdiff1d(np.arange(full.shape[1]), columns)
    np.testing.assert_array_equal(reduced[:, others], full[:, others])  # forearm, wrist
    changed = np.degrees(np.abs(reduced - full)).max(axis=0)
    assert changed[columns].max() > 5  # the manipulation shows
    # A stricter threshold reduces less.
    mild = build_motion(
        ClipRequest("word", "ELEPHANT", {"hand": "reduced", "hand_range_deg": 1, "hand_rmsd": 0.1})
    ).motion
    assert np.abs(mild - full).sum() < np.abs(reduced - full).sum()


def test_reduce_command_writes_the_motion_and_seed_002_tables(tmp_path, capsys):
    out, report = tmp_path / "reduced.bvh", tmp_path / "report"
    assert (
        main(
            [
                "reduce",
                "--spell",
                "HEAVEN",
                "--range-deg",
                "5",
                "--rmsd",
                "0.5",
                "--out",
                str(out),
                "--report",
                str(report),
            ]
        )
        == 0
    )
    printed = capsys.readouterr().out
    assert "of 25 DOFs free" in printed
    motion = read_hand_motion(out)
    assert motion.rate_hz == pytest.approx(30.0) and len(motion.names) == 25
    with (report / "steps.csv").open() as handle:
        steps = list(csv.DictReader(handle))
    assert [s["published_dofs_of_50"] for s in steps] == ["39", "27", "31", "15"]
    assert int(steps[-1]["dofs"]) <= int(steps[0]["dofs"])
    with (report / "errors.csv").open() as handle:
        errors = {row["curve"]: row for row in csv.DictReader(handle)}
    assert all(float(r["rms_error_deg"]) == 0 for r in errors.values() if r["role"] == "free")
    assert "engine's spelling of HEAVEN" in (report / "report.md").read_text()
    assert (report / "dofs-vs-error.png").stat().st_size > 1000
    # The reduced BVH reads back and reduces again.
    assert main(["reduce", str(out), "--range-deg", "5", "--rmsd", "0.5"]) == 0
    assert "rebuilt)" in capsys.readouterr().out


def test_bad_motions_are_named(tmp_path, capsys):
    (tmp_path / "x.txt").write_text("no")
    assert main(["reduce", str(tmp_path / "x.txt")]) == 2
    assert "a .bvh or a .pose file" in capsys.readouterr().err
    assert main(["reduce"]) == 2
    assert "--spell WORD" in capsys.readouterr().err


def test_reconstruct_command_ranks_markers_and_reports_errors_by_count(tmp_path, capsys):
    out, report = tmp_path / "rebuilt.bvh", tmp_path / "report"
    assert (
        main(
            [
                "reconstruct",
                "--spell",
                "CAB",
                "--markers",
                "3",
                "--out",
                str(out),
                "--report",
                str(report),
            ]
        )
        == 0
    )
    assert read_hand_motion(out).rate_hz == pytest.approx(120.0)
    with (report / "marker-ranking.csv").open() as handle:
        ranking = list(csv.DictReader(handle))
    assert len(ranking) == 13 and ranking[0]["marker"].endswith("_tip")
    with (report / "errors-by-markers.csv").open() as handle:
        errors = [float(row["error_cm"]) for row in csv.DictReader(handle)]
    assert len(errors) == 13 and errors[-1] < errors[0]
    assert (report / "markers-vs-error.png").stat().st_size > 1000
