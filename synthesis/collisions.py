"""Finger self-intersection: do two digits' phalanges pass through each other?

Each phalanx is a capsule (a segment between two joints with the avatar's radius there);
two capsules of different digits intersect when their axes come closer than the sum of
their radii. Penetration is that shortfall in metres. Letter contacts (F, O, D…) touch
by design and overlap a few millimetres; a finger passing *through* another overlaps by
much more, which is what the check is for (spec 02: no finger segment may pass through
another in a synthesized transition).
"""

import itertools
from dataclasses import dataclass

import numpy as np

from synthesis.hand import FINGERS, HandModel

# Radii (m) at the start of each phalanx, like the avatar's skin (synthesis.avatar.hand).
_THUMB = (("thumb_mcp", "thumb_ip", 0.0100), ("thumb_ip", "thumb_tip", 0.0088))
_FINGER_RADII_M = {"index": 0.0088, "middle": 0.0090, "ring": 0.0085, "pinky": 0.0076}


@dataclass(frozen=True)
class Intersection:
    """Two phalanges of different digits overlapping by *depth_m* in frame *frame*."""

    frame: int
    first: str
    second: str
    depth_m: float


def _segments(model: HandModel) -> list[tuple[str, str, str, float]]:
    """Return (digit, start joint, end joint, radius) for every phalanx."""
    segments = [("thumb", a, b, r) for a, b, r in _THUMB]
    for finger in FINGERS:
        joints = (f"{finger}_mcp", f"{finger}_pip", f"{finger}_dip", f"{finger}_tip")
        for a, b in itertools.pairwise(joints):
            segments.append((finger, a, b, _FINGER_RADII_M[finger]))
    return segments


def segment_distances(p1, q1, p2, q2) -> np.ndarray:
    """Return the closest distance between segments p1–q1 and p2–q2, shapes (..., 3)."""
    d1, d2, r = q1 - p1, q2 - p2, p1 - p2
    a = np.sum(d1 * d1, axis=-1)
    e = np.sum(d2 * d2, axis=-1)
    f = np.sum(d2 * r, axis=-1)
    c = np.sum(d1 * r, axis=-1)
    b = np.sum(d1 * d2, axis=-1)
    denominator = a * e - b * b
    # Closest points of the infinite lines, clamped to the first segment …
    with np.errstate(divide="ignore", invalid="ignore"):
        s = np.where(denominator > 1e-12, np.clip((b * f - c * e) / denominator, 0, 1), 0.0)
        t = (b * s + f) / e
    # … then to the second, and back to the first where the second clamps.
    t_clamped = np.clip(t, 0.0, 1.0)
    s = np.where(t_clamped != t, np.clip((b * t_clamped - c) / a, 0.0, 1.0), s)
    closest_1 = p1 + s[..., None] * d1
    closest_2 = p2 + t_clamped[..., None] * d2
    return np.linalg.norm(closest_1 - closest_2, axis=-1)


def finger_intersections(
    model: HandModel, dofs_rad: np.ndarray, tolerance_m: float = 0.004
) -> list[Intersection]:
    """Return every overlap deeper than *tolerance_m* between digits, over frames."""
    positions = model.pose(np.atleast_2d(dofs_rad)).positions_m
    segments = _segments(model)
    index = model.skeleton.index
    found = []
    for i, (digit_i, a_i, b_i, r_i) in enumerate(segments):
        for digit_j, a_j, b_j, r_j in segments[i + 1 :]:
            if digit_i == digit_j:
                continue
            distance = segment_distances(
                positions[:, index(a_i)], positions[:, index(b_i)],
                positions[:, index(a_j)], positions[:, index(b_j)],
            )  # fmt: skip
            depth = r_i + r_j - distance
            for frame in np.flatnonzero(depth > tolerance_m):
                found.append(
                    Intersection(int(frame), f"{a_i}–{b_i}", f"{a_j}–{b_j}", float(depth[frame]))
                )
    return sorted(found, key=lambda hit: (hit.frame, -hit.depth_m))
