"""Test the simple default spelling timing: holds, transitions, paths, doubled letters."""

import numpy as np
import pytest

from synthesis.alphabet import AlphabetError, letter_pose
from synthesis.hand import HandModel
from synthesis.spelling import SpellingTiming, spell, spelling_keys


def test_frame_count_follows_the_timing():
    timing = SpellingTiming(hold_ms=200, transition_ms=100, path_ms=400, rest_ms=250)
    frames = spell("AB", rate_hz=60, timing=timing)
    # rest 250, (transition 100 + hold 200) × 2, transition 100, rest 250 = 1.2 s:
    # 72 frame intervals, 73 frames.
    assert len(frames) == 73


def test_holds_show_the_letters():
    timing = SpellingTiming()
    times, _ = spelling_keys("BC", timing=timing)
    frames = spell("BC", rate_hz=100, timing=timing)
    for k, letter in enumerate("BC"):
        middle = times[1 + 2 * k] + timing.hold_ms / 2000
        assert np.allclose(frames[round(middle * 100)], letter_pose(letter), atol=1e-9)


def test_doubled_letters_slide_outward_and_paths_move():
    model = HandModel()
    slide = model.dof_names.index("forearm_tilt_side")
    _, poses = spelling_keys("LL")  # keys: rest, L held (2 keys), L again (2 keys), rest
    assert poses[3, slide] - poses[1, slide] == pytest.approx(np.radians(7.0))
    assert np.array_equal(np.delete(poses[3], slide), np.delete(poses[1], slide))
    twist = model.dof_names.index("forearm_twist")
    frames = spell("J")
    assert np.ptp(frames[:, twist]) > np.radians(60)  # J turns the forearm


def test_stays_within_the_joint_limits_and_rejects_non_letters():
    frames = spell("QUIZ")
    low, high = HandModel().limits_rad
    assert np.all(frames >= low - 1e-12) and np.all(frames <= high + 1e-12)
    with pytest.raises(AlphabetError, match="'3' is not a letter"):
        spell("B3")
    with pytest.raises(AlphabetError, match="empty"):
        spell("  ")
