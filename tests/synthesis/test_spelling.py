"""Test spelling a word with a timing: holds, transitions, paths, doubled letters."""

import numpy as np
import pytest

from synthesis.fingerspelling.alphabet import AlphabetError, letter_pose
from synthesis.fingerspelling.spelling import simple_timing, spell, spelling_keys
from synthesis.rigs.hand import HandModel
from synthesis.timing import WordTiming, constant_timing


def test_frame_count_follows_the_timing():
    timing = WordTiming(("A", "B"), (200, 200), (100,))
    frames = spell("AB", rate_hz=60, timing=timing, lead_ms=250)
    # rest 100, lead 250, hold 200, transition 100, hold 200, lead 250, rest 100 = 1.2 s:
    # 72 intervals.
    assert len(frames) == 73
    # The clip opens and closes on a still, relaxed hand (6 frames of rest at 60 fps).
    assert np.allclose(frames[:7], frames[0]) and np.allclose(frames[-7:], frames[-1])
    assert np.allclose(frames[0], frames[-1])
    constant = spell("AB", rate_hz=60, timing=constant_timing("AB"), lead_ms=0)
    assert len(constant) == int((243 + 250 + 800) * 60 / 1000) + 1  # 1.293 s: 77 intervals


def test_holds_show_the_letters():
    timing = WordTiming(("B", "C"), (300, 240), (150,))
    frames = spell("BC", rate_hz=100, timing=timing, lead_ms=200)
    for start_ms, hold_ms, name in ((300, 300, "B"), (750, 240, "C")):
        middle = round((start_ms + hold_ms / 2) / 10)
        assert np.allclose(frames[middle], letter_pose(name), atol=1e-9)


def test_doubled_letters_slide_outward_and_paths_move():
    model = HandModel()
    slide = model.dof_names.index("forearm_tilt_side")
    # rest (2 keys), L (2 keys), L again (2 keys), rest (2 keys)
    _, poses, _ = spelling_keys(simple_timing("LL"))
    assert poses[4, slide] - poses[2, slide] == pytest.approx(np.radians(7.0))
    assert np.array_equal(np.delete(poses[4], slide), np.delete(poses[2], slide))
    twist = model.dof_names.index("forearm_twist")
    frames = spell("J")
    assert np.ptp(frames[:, twist]) > np.radians(60)  # J turns the forearm


def test_stays_within_the_joint_limits_and_rejects_bad_input():
    frames = spell("QUIZ")
    low, high = HandModel().limits_rad
    assert np.all(frames >= low - 1e-12) and np.all(frames <= high + 1e-12)
    with pytest.raises(AlphabetError, match="'3' is not a letter"):
        spell("B3")
    with pytest.raises(AlphabetError, match="empty"):
        spell("  ")
    with pytest.raises(ValueError, match="The timing is for AB, not BA"):
        spell("BA", timing=constant_timing("AB"))
