"""Resample, trim and time-warp motions, and interpolate between poses with slerp.

Everything rests on :func:`sample`: a motion's value at arbitrary times, with joint
rotations interpolated on the sphere (slerp) and positions linearly. Times that fall
exactly on a frame return that frame's values unchanged. Curves of angles (DOF vectors)
are sampled linearly by :func:`sample_curves` and :func:`resample_curves`;
:func:`reset_root` puts a motion's root at the standard position.
"""

from collections.abc import Callable, Sequence

import numpy as np
from scipy.interpolate import PchipInterpolator, interp1d
from scipy.spatial.transform import Rotation

from synthesis.skeleton.motion import Motion
from synthesis.skeleton.rotations import euler_angles
from synthesis.skeleton.skeleton import Skeleton

Warp = Callable[[np.ndarray], np.ndarray]


def minimum_jerk(fraction: np.ndarray) -> np.ndarray:
    """Return the minimum-jerk profile ``10s³ − 15s⁴ + 6s⁵`` of *fraction* s, clipped to
    [0, 1] (Flash and Hogan's reach: a move from rest to rest)."""
    s = np.clip(fraction, 0.0, 1.0)
    return 10 * s**3 - 15 * s**4 + 6 * s**5


def _slerp_groups(skeleton: Skeleton) -> dict[str, np.ndarray]:
    """Return, per Euler order, the value columns of joints with three rotation channels."""
    groups = {}
    for order, (_, columns) in skeleton.rotation_groups.items():
        if len(order) == 3:
            groups[order] = columns
    return groups


def sample(motion: Motion, times_s: np.ndarray) -> np.ndarray:
    """Return the motion's channel values at *times_s*, shape (n_times, n_channels).

    Times are clamped to the clip. Three-channel rotations are slerped; other channels
    (positions, single-axis rotations) are interpolated linearly. Euler angles are
    brought to the 360° turn nearest the linear interpolation, so curves stay
    continuous.
    """
    times = np.asarray(times_s, dtype=np.float64).reshape(-1)
    if motion.n_frames == 0:
        raise ValueError("Cannot sample a motion without frames.")
    position = np.clip(times / motion.frame_time_s, 0.0, motion.n_frames - 1)
    low = np.floor(position).astype(np.intp)
    high = np.minimum(low + 1, motion.n_frames - 1)
    fraction = position - low
    values = motion.values
    linear = values[low] + (values[high] - values[low]) * fraction[:, None]
    result = linear.copy()
    between = fraction > 0
    if between.any():
        for order, columns in _slerp_groups(motion.skeleton).items():
            k = len(columns) // 3
            a = np.radians(values[low[between]][:, columns]).reshape(-1, 3)
            b = np.radians(values[high[between]][:, columns]).reshape(-1, 3)
            start = Rotation.from_euler(order, a)
            step = (start.inv() * Rotation.from_euler(order, b)).as_rotvec()
            weights = np.repeat(fraction[between], k)[:, None]
            blended = start * Rotation.from_rotvec(step * weights)
            angles = euler_angles(blended, order, degrees=True).reshape(-1, len(columns))
            reference = linear[between][:, columns]
            angles += 360.0 * np.round((reference - angles) / 360.0)
            result[np.ix_(np.flatnonzero(between), columns)] = angles
    exact = fraction == 0
    result[exact] = values[low[exact]]
    return result


def resample(motion: Motion, rate_hz: float) -> Motion:
    """Return the motion sampled at *rate_hz* over the same duration."""
    if not rate_hz > 0:
        raise ValueError(f"Rate must be positive; got {rate_hz!r}.")
    count = int(np.floor(motion.duration_s * rate_hz + 1e-9)) + 1
    return motion.with_values(sample(motion, np.arange(count) / rate_hz), 1.0 / rate_hz)


def trim(motion: Motion, start_s: float = 0.0, end_s: float | None = None) -> Motion:
    """Return the frames from *start_s* to *end_s* (inclusive, nearest frames)."""
    end_s = motion.duration_s if end_s is None else end_s
    if end_s < start_s:
        raise ValueError(f"Trim end {end_s} s is before its start {start_s} s.")
    first = max(0, round(start_s / motion.frame_time_s))
    last = min(motion.n_frames - 1, round(end_s / motion.frame_time_s))
    return motion.with_values(motion.values[first : last + 1])


def piecewise_linear_warp(target_s: Sequence[float], source_s: Sequence[float]) -> Warp:
    """Return a warp sending each target time to a source time, linear between keys.

    Keys must increase in both lists: ``target_s[i]`` of the new motion shows what
    ``source_s[i]`` of the old one showed (seed 000 §4.3: holds and transitions of a
    recording moved onto predicted timing).
    """
    target, source = _check_keys(target_s, source_s)
    return lambda times: np.interp(times, target, source)


def monotone_spline_warp(target_s: Sequence[float], source_s: Sequence[float]) -> Warp:
    """Return a smooth warp through the keys that never runs backwards (PCHIP)."""
    target, source = _check_keys(target_s, source_s)
    spline = PchipInterpolator(target, source, extrapolate=False)
    return lambda times: spline(np.clip(times, target[0], target[-1]))


def _check_keys(target_s: Sequence[float], source_s: Sequence[float]):
    target = np.asarray(target_s, dtype=np.float64)
    source = np.asarray(source_s, dtype=np.float64)
    if target.shape != source.shape or target.ndim != 1 or target.size < 2:
        raise ValueError("A warp needs two equally long lists of at least two key times.")
    if np.any(np.diff(target) <= 0) or np.any(np.diff(source) < 0):
        raise ValueError("Warp keys must increase (target strictly, source never decrease).")
    return target, source


def time_warp(
    motion: Motion, warp: Warp, duration_s: float, rate_hz: float | None = None
) -> Motion:
    """Return a motion of *duration_s* whose frame at time t shows the source at warp(t)."""
    rate = motion.rate_hz if rate_hz is None else rate_hz
    count = int(np.floor(duration_s * rate + 1e-9)) + 1
    times = np.arange(count) / rate
    return motion.with_values(sample(motion, warp(times)), 1.0 / rate)


def interpolate_poses(
    skeleton: Skeleton, pose_a: np.ndarray, pose_b: np.ndarray, fractions: np.ndarray
) -> np.ndarray:
    """Return poses between two channel-value vectors at *fractions* in [0, 1] (slerp)."""
    pair = Motion(skeleton, np.stack([pose_a, pose_b]), 1.0)
    return sample(pair, np.clip(np.asarray(fractions, dtype=np.float64), 0.0, 1.0))


def reset_root(motion: Motion) -> Motion:
    """Return *motion* with its root's position and orientation set to zero (seed 004 §3.2.3).

    The body then stands at the origin facing the camera, whatever the capture's room.
    """
    root = next(i for i, joint in enumerate(motion.skeleton.joints) if joint.parent < 0)
    values = np.array(motion.values)
    values[:, motion.skeleton.channel_slices()[root]] = 0.0
    return Motion(motion.skeleton, values, motion.frame_time_s)


def sample_curves(values: np.ndarray, rate_hz: float, times_s: np.ndarray) -> np.ndarray:
    """Return curves (n_frames, n_curves) sampled at *rate_hz*, read at *times_s* (linear,
    held at the first and last frame outside the clip)."""
    values = np.asarray(values, dtype=float)
    frames_s = np.arange(len(values)) / rate_hz
    read = interp1d(
        frames_s,
        values,
        axis=0,
        bounds_error=False,
        fill_value=(values[0], values[-1]),
        assume_sorted=True,
    )
    return read(np.asarray(times_s, dtype=float))


def resample_curves(values: np.ndarray, rate_hz: float, new_rate_hz: float) -> np.ndarray:
    """Return curves (n_frames, n_curves) at *new_rate_hz* over the same duration (linear)."""
    if abs(new_rate_hz - rate_hz) < 1e-9:
        return np.asarray(values, dtype=float)
    duration_s = (len(values) - 1) / rate_hz
    count = int(np.floor(duration_s * new_rate_hz + 1e-9)) + 1
    return sample_curves(values, rate_hz, np.arange(count) / new_rate_hz)
