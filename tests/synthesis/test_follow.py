"""Test the following close-up: every letter inside and large, still on letters."""

import numpy as np
import pytest

from synthesis.avatar.hand_mesh import hand_avatar
from synthesis.fingerspelling.spelling import hold_times_s
from synthesis.render.follow import follow_hand
from synthesis.render.framing import measure_framing
from synthesis.render.scene import CameraPath, hand_close_up
from synthesis.techniques import ClipRequest, build_motion

RATE_HZ = 30.0


def _word(word: str):
    build = build_motion(ClipRequest("word", word, {"timing": "constant"}, rate_hz=RATE_HZ))
    return np.asarray(build.motion), hold_times_s(build.timing)


@pytest.fixture(scope="module")
def avatar():
    return hand_avatar("right")


@pytest.mark.parametrize("word", ["PSYCHIATRY", "JAZZ", "GUQ"])
def test_every_letter_stays_inside_and_fills_the_frame(avatar, word):
    """Issue 16: no hand vertex outside in any frame, the hand ≥ 45 % of the frame's
    height at every hold (measured: 50 %, 54 %, 47 % at the smallest; the fixed
    close-up gave 22 %, 25 %, 21 % and put P, G and Q partly outside)."""
    motion, holds = _word(word)
    path = follow_hand(avatar, motion, hand_close_up(), RATE_HZ)
    assert isinstance(path, CameraPath) and len(path) == len(motion)
    framing = measure_framing(avatar, path, motion)
    assert not framing.hand_outside.any()
    middles = np.round(holds.mean(axis=1) * RATE_HZ).astype(int)
    assert framing.hand_share[middles].min() >= 0.45
    fixed = measure_framing(avatar, hand_close_up(), motion)
    assert fixed.hand_share[middles].min() < 0.3


def _filmed(motion, word):
    from synthesis.techniques import filming

    return filming("hand", "right", motion, RATE_HZ, 640, 480, word)[1]


def test_the_camera_holds_still_on_letters_and_leaves_a_z_its_path(avatar):
    motion, holds = _word("AZ")
    path = _filmed(motion, "AZ")
    moved_m = np.linalg.norm(np.diff(path.eye_m, axis=0), axis=1)
    start, end = np.round(holds * RATE_HZ).astype(int)[1]  # the Z's hold: its path
    # The fingertip draws the Z; the camera moves a seventh as far meanwhile at most
    # (measured: 5 cm against 54 cm).
    tip = avatar.rig.skeleton.index("index_tip")
    drawn_m = np.linalg.norm(
        np.diff(avatar.rig.pose(motion[start:end]).positions_m[:, tip, :2], axis=0), axis=1
    ).sum()
    assert drawn_m > 0.05
    assert moved_m[start:end].sum() < 0.15 * drawn_m
    # Between letters the camera pans (up to 56 mm a frame in PSYCHIATRY); once the hand
    # has arrived on a letter, the camera stands still until it leaves.
    motion, holds = _word("PSYCHIATRY")
    path = _filmed(motion, "PSYCHIATRY")
    moved_m = np.linalg.norm(np.diff(path.eye_m, axis=0), axis=1)
    assert moved_m.max() > 0.03
    for start, end in np.round(holds * RATE_HZ).astype(int):
        assert moved_m[start + 2 : end - 2].max() < 1e-6


def test_a_hand_that_is_never_still_is_filmed_from_one_place_where_it_can_be(avatar):
    """A recording's tremor keeps the hand from ever being still: the camera stands
    still while the hand stays in view, and pans only to keep it there (measured: still
    in 44 % of the frames of AB, the B needing a pan)."""
    motion, _ = _word("AB")
    rng = np.random.default_rng(0)
    shaky = motion + rng.normal(0.0, np.radians(1.5), motion.shape)
    path = follow_hand(avatar, shaky, hand_close_up(), RATE_HZ)
    assert not measure_framing(avatar, path, shaky).hand_outside.any()
    moved_m = np.linalg.norm(np.diff(path.eye_m, axis=0), axis=1)
    assert (moved_m < 1e-9).mean() > 0.3


def test_conditions_of_a_word_open_and_close_on_the_same_frame():
    """Clip hygiene: every timing of a word starts and ends with the same hand seen by
    the same camera (the close-up's scale is the word's letters', not the clip's); so does
    the camera of its simulated capture, whose hand carries the capture's noise."""
    from synthesis.render.framing import hand_vertices
    from synthesis.techniques import filming

    ends = []
    for parameters in (
        {"timing": "constant"},
        {"timing": "variable"},
        {"timing": "mocap", "source": "simulated"},
    ):
        request = ClipRequest("word", "DAVID", parameters, rate_hz=RATE_HZ)
        motion = build_motion(request).motion
        avatar, path = filming("hand", "right", motion, RATE_HZ, 640, 480, "DAVID")
        hand = hand_vertices(avatar, motion)
        ends.append((path.eye_m[[0, -1]], hand[[0, -1]]))
    for eyes, _ in ends[1:]:
        np.testing.assert_allclose(eyes, ends[0][0], atol=1e-9)
    np.testing.assert_allclose(ends[1][1], ends[0][1], atol=1e-6)


def test_a_path_needs_one_eye_and_target_per_frame():
    with pytest.raises(ValueError, match=r"\(n, 3\)"):
        CameraPath("bad", np.zeros((3, 3)), np.zeros((2, 3)), 10.0)
    path = CameraPath("two", np.array([[0, 0, 1.0], [0.1, 0, 1.0]]), np.zeros((2, 3)), 10.0)
    assert path.at(1).eye_m == (0.1, 0.0, 1.0) and len(path.every(1, 2)) == 1


def test_a_path_renders_each_frame_as_its_own_camera_would(avatar, renderable):
    from synthesis.render.renderer import Renderer

    motion, _ = _word("GO")
    path = follow_hand(avatar, motion, hand_close_up(), RATE_HZ, 160, 120)
    with Renderer(avatar, path, 160, 120) as renderer:
        frames = list(renderer.frames(motion))
    with pytest.raises(ValueError, match="camera path has"), Renderer(avatar, path, 160, 120) as r:
        next(r.frames(motion[:5]))
    for k in (0, len(motion) // 2, len(motion) - 1):
        with Renderer(avatar, path.at(k), 160, 120) as renderer:
            assert np.array_equal(renderer.frame(motion[k]), frames[k])
