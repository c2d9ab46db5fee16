"""A fingerspelling close-up that follows the hand: still on each letter, panning between.

No fixed camera both shows a fist large (a fist is 10 cm tall, so 45 % of the frame
height means a frame 23 cm tall) and keeps every letter in the frame: G and H point the
hand sideways 20–34 cm from where B stands, P and Q drop it 25 cm (issue 16, measured
on the hand avatar). So the close-up camera pans parallel to the image plane, as a
camera operator filming a signer's hand would: it stays on the hand's whole extent over
a stretch of time (a J or Z path, the bounce of a double letter) and moves between
letters, never letting a vertex of the hand leave the frame.

How: with the camera looking along −z from (cx, cy, cz), a point p is inside the frame
while |p_x − cx| ≤ X·(cz − p_z) and |p_y − cy| ≤ Y·(cz − p_z) (X, Y the tangents of the
half fields of view less a margin), so each frame's hand vertices bound the centre to an
interval per axis. The distance cz is one for the clip, the nearest at which every
frame's interval is open, except nearer where a held letter would be small. The hand
is still (a hold) or moving; on each still stretch the camera stands at the middle of
the centres common to the stretch, and over each moving stretch between two it eases
from one to the other, clamped into each frame's own interval, so a hold is filmed by
a camera at rest and a J or Z draws its path across the frame.
"""

import itertools

import numpy as np

from synthesis.avatar.model import Avatar
from synthesis.render.framing import hand_vertices
from synthesis.render.scene import CameraPath, CameraPreset
from synthesis.skeleton.kinematics import Pose

# Free space between the hand and the frame's edges, as a share of the frame.
MARGIN_SHARE = 0.03
# The hand's height at a hold should be at least this share of the frame's (issue 16
# asks 45 %); the camera comes closer where a letter would be smaller.
HOLD_SHARE = 0.46
# A long lens: at 30° the camera stood 25 cm from the hand, and a letter pointing at
# it (P, Q) loomed twice as large as an upright one.
YFOV_DEG = 10.0
# The hand is still while no vertex moves faster than this (a hold's tremor is slower).
STILL_M_S = 0.05


def _extremes(points: np.ndarray, tangent: float, axis: int) -> tuple[np.ndarray, np.ndarray]:
    """Return per frame max(p + t·p_z) and min(p − t·p_z) over *points* (n_frames, n, 3)
    on *axis*: the camera centre c at distance z keeps them all inside while
    max(p + t·p_z) − t·z ≤ c ≤ min(p − t·p_z) + t·z."""
    along, depth = points[..., axis], points[..., 2]
    return (along + tangent * depth).max(axis=1), (along - tangent * depth).min(axis=1)


def _runs(still: np.ndarray) -> list[tuple[int, int, bool]]:
    """Return the runs (start, stop, still) of equal values of *still* (n_frames,)."""
    edges = np.flatnonzero(np.diff(still.astype(np.int8))) + 1
    bounds = np.concatenate([[0], edges, [len(still)]])
    return [(int(a), int(b), bool(still[a])) for a, b in itertools.pairwise(bounds)]


def _ease(values_at_rest: np.ndarray, runs) -> np.ndarray:
    """Return per frame the value of its still run, eased (smoothstep) across each moving
    run from the still value before it to the one after (held at the clip's ends)."""
    out = np.empty(len(values_at_rest))
    rests = [(a, b) for a, b, still in runs if still]
    for a, b, still in runs:
        if still:
            out[a:b] = values_at_rest[a]
            continue
        before = [r for r in rests if r[1] <= a]
        after = [r for r in rests if r[0] >= b]
        first = values_at_rest[before[-1][0]] if before else None
        last = values_at_rest[after[0][0]] if after else None
        first = last if first is None else first
        last = first if last is None else last
        u = (np.arange(a, b) - a + 1) / (b - a + 1)
        out[a:b] = first + (last - first) * u * u * (3 - 2 * u)
    return out


def _per_run(values: np.ndarray, runs, reduce) -> np.ndarray:
    """Return per frame *reduce* of *values* over its still run (moving frames keep theirs)."""
    out = values.copy()
    for a, b, still in runs:
        if still:
            out[a:b] = reduce(values[a:b])
    return out


def follow_hand(
    avatar: Avatar,
    motion: np.ndarray | Pose,
    base: CameraPreset,
    rate_hz: float,
    width: int = 640,
    height: int = 480,
    margin_share: float = MARGIN_SHARE,
    hold_share: float = HOLD_SHARE,
    yfov_deg: float = YFOV_DEG,
) -> CameraPath:
    """Return a camera path (one camera per frame of *motion*) that follows the hand.

    *motion* is DOF vectors (n_frames, n_dofs) or a Pose of *avatar*'s skeleton at
    *rate_hz*; the path looks along −z through a *yfov_deg* lens at *width* × *height*.
    *base* is the fixed close-up the path replaces (its name is kept).
    """
    points = hand_vertices(avatar, motion)
    half = np.tan(np.radians(yfov_deg) / 2)
    tangents = (half * width / height * (1 - 2 * margin_share * height / width),
                half * (1 - 2 * margin_share))  # fmt: skip
    speed = np.zeros(len(points))
    if len(points) > 1:
        step = np.linalg.norm(np.diff(points, axis=0), axis=-1).max(axis=1) * rate_hz
        speed = np.maximum(np.concatenate([[step[0]], step]), np.concatenate([step, [step[-1]]]))
    runs = _runs(speed < STILL_M_S)
    extremes = [_extremes(points, tangent, axis) for axis, tangent in enumerate(tangents)]
    # The nearest distance per frame at which some centre fits the hand, on either axis.
    needed = np.max(
        [(upper - lower) / (2 * t) for (upper, lower), t in zip(extremes, tangents, strict=True)],
        axis=0,
    )
    needed = np.maximum(needed, points[..., 2].max(axis=1) + 0.05)
    # One distance for the clip where it can be; nearer where a held letter would be
    # small. A hand that needs the camera at z (filling 1 − 2·margin of the frame) fills
    # hold_share of it from depth + (z − depth)·(1 − 2·margin) / hold_share.
    depth = points[..., 2].mean(axis=1)
    close_enough = depth + (needed - depth) * (1 - 2 * margin_share) / hold_share
    at_rest = _per_run(np.minimum(needed.max(), close_enough), runs, np.min)
    eye_z = np.maximum(_ease(np.maximum(at_rest, _per_run(needed, runs, np.max)), runs), needed)
    centre = []
    for (upper, lower), tangent in zip(extremes, tangents, strict=True):
        low, high = upper - tangent * eye_z, lower + tangent * eye_z
        common_low, common_high = _per_run(low, runs, np.max), _per_run(high, runs, np.min)
        aim = np.where(common_low <= common_high, (common_low + common_high) / 2,
                       (low + high) / 2)  # fmt: skip
        centre.append(np.clip(_ease(aim, runs), low, high))
    eye = np.column_stack([centre[0], centre[1], eye_z])
    target = eye.copy()
    target[:, 2] = 0.0
    return CameraPath(f"{base.name} (following the hand)", eye, target, yfov_deg)
