"""Test recordings: retiming onto a model's timing, training on them, duration tables."""

import numpy as np
import pytest

from synthesis.fingerspelling.spelling import spell
from synthesis.rigs.hand import HandModel
from synthesis.skeleton.bvh import write_bvh
from synthesis.skeleton.motion import Motion
from synthesis.timing import WordTiming, constant_timing, extract, published_model
from synthesis.timing.recordings import (
    Recording,
    duration_table,
    format_table,
    retime,
    train_on_recordings,
)


def _save(folder, word: str, rng) -> WordTiming:
    holds = rng.uniform(70, 150, len(word))
    holds[-1] += 150
    timing = WordTiming(tuple(word), tuple(holds), tuple(rng.uniform(130, 280, len(word) - 1)))
    model = HandModel()
    dofs = spell(word, rate_hz=60, timing=timing, lead_ms=300)
    write_bvh(Motion(model.skeleton, model.channel_values(dofs), 1 / 60), folder / f"{word}.bvh")
    return timing


def test_retiming_moves_the_holds_onto_the_new_timing(tmp_path):
    _save(tmp_path, "DAVID", np.random.default_rng(2))
    recording = Recording.read(tmp_path / "DAVID.bvh")
    assert recording.word == "DAVID"
    target = constant_timing("DAVID")
    warped = retime(recording, target)
    found = extract(warped, "DAVID").timing
    assert found.total_ms == pytest.approx(target.total_ms, abs=40)
    assert found.hold_ms[-1] == pytest.approx(800, abs=40)
    with pytest.raises(ValueError, match="for HEAVEN, not DAVID"):
        retime(recording, constant_timing("HEAVEN"))


def test_training_on_recordings_and_the_duration_table(tmp_path):
    rng = np.random.default_rng(3)
    words = ("HEAVEN", "GUITAR", "DAVID", "VICTOR", "MICHAEL", "ELEPHANT")
    truth = {w: _save(tmp_path, w, rng) for w in words}
    recordings = [Recording.read(tmp_path / f"{w}.bvh") for w in words]
    model, report = train_on_recordings(recordings)
    assert report.holds.nobs == sum(len(w) for w in words)
    assert model.metadata["training_holds"] == report.holds.nobs
    rows = duration_table(recordings, published_model())
    assert [r["word"] for r in rows] == [*words, "mean |error|"]
    for row in rows[:-1]:
        assert row["mocap_ms"] == pytest.approx(truth[row["word"]].total_ms, abs=60)
        assert row["normalized_ms"] == pytest.approx(row["variable_ms"])
    table = format_table(rows)
    assert table.splitlines()[0].startswith("| word | mocap (ms) |")
    assert "| mean |error| |" in table


def test_a_hand_motion_read_back_from_bvh_is_the_motion_written(tmp_path):
    """BVH End Sites have no names; the hand still reads back as the rig's own skeleton,
    so its poses (and the holds found in them) are exactly the written ones."""
    from synthesis.rigs.retarget import retarget
    from synthesis.skeleton.bvh import read_bvh
    from synthesis.timing import simulate_recording

    motion, _ = simulate_recording("PSYCHIATRY", np.random.default_rng(1), rate_hz=30.0)
    write_bvh(motion, tmp_path / "PSYCHIATRY.bvh")
    again = read_bvh(tmp_path / "PSYCHIATRY.bvh")
    assert again.skeleton.names != motion.skeleton.names  # End Sites renamed
    model = HandModel()
    np.testing.assert_allclose(
        retarget(again, model).quaternions, retarget(motion, model).quaternions, atol=1e-9
    )
    assert Recording.read(tmp_path / "PSYCHIATRY.bvh").extraction.timing.word == "PSYCHIATRY"


def test_a_recording_whose_holds_are_not_found_plays_only_as_performed(tmp_path):
    from synthesis.techniques import ClipRequest, build_motion
    from synthesis.timing import ExtractionError

    _save(tmp_path, "DAVID", np.random.default_rng(2))
    path = str(tmp_path / "DAVID.bvh")
    # Read as another word, the holds cannot be found: as performed it still plays...
    mocap = ClipRequest.from_parameters(
        "word", "HEAVEN", {"source": "recording", "recording": path, "timing": "mocap"}
    )
    build = build_motion(mocap)
    assert build.timing is None and len(build.motion.quaternions) > 0
    # ...but a condition that retimes it names the problem.
    retimed = ClipRequest.from_parameters(
        "word", "HEAVEN", {"source": "recording", "recording": path, "timing": "constant"}
    )
    with pytest.raises(ExtractionError, match="letters of HEAVEN"):
        build_motion(retimed)
