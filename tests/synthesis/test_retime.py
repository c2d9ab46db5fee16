"""Test sampling, resampling, trimming, time warps and slerp between poses."""

from pathlib import Path

import numpy as np
import pytest
from scipy.spatial.transform import Rotation, Slerp

from synthesis import (
    Joint,
    Motion,
    Skeleton,
    interpolate_poses,
    monotone_spline_warp,
    piecewise_linear_warp,
    read_bvh,
    resample,
    sample,
    time_warp,
    trim,
)

DATA = Path(__file__).parent / "data"


@pytest.fixture
def clip() -> Motion:
    motion = read_bvh(DATA / "seed004_figure_b1.bvh")
    rng = np.random.default_rng(3)
    return motion.with_values(rng.uniform(-90, 90, (13, 21)), 1 / 120)


def test_sampling_at_frame_times_is_exact(clip):
    assert np.array_equal(sample(clip, clip.times_s), clip.values)
    assert resample(clip, clip.rate_hz) == clip


def test_halving_the_rate_keeps_every_second_frame(clip):
    half = resample(clip, 60)
    assert half.n_frames == 7 and half.frame_time_s == 1 / 60
    assert np.array_equal(half.values, clip.values[::2])


def test_rotations_are_slerped_like_scipy(clip):
    times = np.array([0.25, 1.5, 7.9]) * clip.frame_time_s
    sampled = sample(clip, times)
    for joint, where in zip(clip.skeleton.joints, clip.skeleton.channel_slices(), strict=True):
        columns = [where.start + k for k, c in enumerate(joint.channels) if c.endswith("rotation")]
        if len(columns) != 3:
            continue
        keys = Rotation.from_euler(joint.rotation_order, clip.values[:, columns], degrees=True)
        expected = Slerp(clip.times_s, keys)(times).as_matrix()
        got = Rotation.from_euler(joint.rotation_order, sampled[:, columns], degrees=True)
        assert np.allclose(got.as_matrix(), expected, atol=1e-10)


def test_positions_are_linear(clip):
    middle = sample(clip, [0.5 * clip.frame_time_s])[0]
    assert np.allclose(middle[:3], (clip.values[0, :3] + clip.values[1, :3]) / 2)


def test_angles_stay_continuous_across_180_degrees():
    skeleton = Skeleton((Joint("j", -1, (0, 0, 0), ("Zrotation", "Xrotation", "Yrotation")),))
    motion = Motion(skeleton, np.array([[170.0, 0, 0], [190.0, 0, 0]]), 1.0)
    assert sample(motion, [0.5])[0] == pytest.approx([180.0, 0, 0])


def test_trim_keeps_the_frames_in_range(clip):
    part = trim(clip, 2 / 120, 5 / 120)
    assert np.array_equal(part.values, clip.values[2:6])
    with pytest.raises(ValueError, match="before its start"):
        trim(clip, 0.05, 0.01)


def test_piecewise_linear_warp_moves_keys_onto_new_times(clip):
    # Source 0–6 frames shown over 0–3 frames (twice as fast), 6–12 over 3–12 (slower).
    dt = clip.frame_time_s
    warp = piecewise_linear_warp([0, 3 * dt, 12 * dt], [0, 6 * dt, 12 * dt])
    warped = time_warp(clip, warp, duration_s=12 * dt)
    assert warped.n_frames == 13
    assert np.array_equal(warped.values[3], clip.values[6])
    assert np.array_equal(warped.values[12], clip.values[12])
    assert np.array_equal(warped.values[0], clip.values[0])


def test_monotone_spline_warp_never_runs_backwards():
    warp = monotone_spline_warp([0, 0.2, 0.5, 1.0], [0, 0.05, 0.6, 0.61])
    source = warp(np.linspace(0, 1, 500))
    assert np.all(np.diff(source) >= -1e-12)
    assert source[0] == 0 and source[-1] == pytest.approx(0.61)


@pytest.mark.parametrize(
    "target, source",
    [([0, 1], [0]), ([0, 0, 1], [0, 1, 2]), ([0, 1, 2], [0, 2, 1]), ([0], [0])],
)
def test_bad_warp_keys_are_rejected(target, source):
    with pytest.raises(ValueError):
        piecewise_linear_warp(target, source)


def test_interpolate_poses_between_two_handshapes():
    skeleton = Skeleton((Joint("finger", -1, (0, 0, 0), ("Zrotation", "Xrotation", "Yrotation")),))
    closed, open_ = np.array([0.0, 90.0, 0.0]), np.array([0.0, 0.0, 0.0])
    poses = interpolate_poses(skeleton, closed, open_, np.array([0.0, 0.5, 1.0]))
    assert np.array_equal(poses[0], closed) and np.array_equal(poses[2], open_)
    assert poses[1] == pytest.approx([0.0, 45.0, 0.0])
