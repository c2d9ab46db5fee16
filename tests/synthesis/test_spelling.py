"""Test the simple default spelling timing: holds, transitions, paths, doubled letters."""

import numpy as np
import pytest

from synthesis.alphabet import AlphabetError, letter_pose
from synthesis.hand import HandModel
from synthesis.spelling import SpellingTiming, spell, spelling_keys


def test_frame_count_follows_the_timing():
    timing = SpellingTiming(hold_ms=200, transition_ms=100, path_ms=400, rest_ms=250)
    frames = spell("AB", rate_hz=60, timing=timing)
    # rest, (transition, hold) × 2, transition, rest = 1.1 s → 66 frames + the first.
    assert len(frames) == 67


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
    _, poses = spelling_keys("LL")
    assert poses[3, slide] == pytest.approx(0.0) and poses[3, slide] != poses[5, slide]
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
