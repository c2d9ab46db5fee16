"""Finger self-intersection: do two digits' phalanges pass through each other?

Each phalanx is a capsule (a segment between two joints with the avatar's radius there);
two capsules of different digits overlap when their axes come closer than the sum of
their radii, by that shortfall in metres (:func:`finger_intersections`). Letters whose
digits press together (S, E, T: the thumb on or between the fingers) overlap by design,
so overlap alone cannot say that a finger went *through* another.

:func:`finger_crossings` does: between two frames, the two axes' closest points are
inside both segments and the signed distance between the axis lines changes sign, that
is the axes met. A finger sliding along another, or around its tip, does not cross;
one passing through it does (spec 02: no finger segment may pass through another in a
synthesized transition).
"""

import itertools
from dataclasses import dataclass

import numpy as np

from synthesis.rigs.hand import FINGERS, HandModel

# Radii (m) at the start of each phalanx, like the avatar's skin (synthesis.avatar.hand_mesh).
_THUMB = (("thumb_mcp", "thumb_ip", 0.0100), ("thumb_ip", "thumb_tip", 0.0088))
_FINGER_RADII_M = {"index": 0.0088, "middle": 0.0090, "ring": 0.0085, "pinky": 0.0076}


@dataclass(frozen=True)
class Crossing:
    """Two phalanges of different digits whose axes pass through each other between
    frame *frame* − 1 and *frame*."""

    frame: int
    first: str
    second: str


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
    depths = overlap_depths_m(model, dofs_rad)
    names = _pairs(model)[3]
    frames, pairs = np.nonzero(depths > tolerance_m)
    found = [
        Intersection(int(f), *names[p], float(depths[f, p]))
        for f, p in zip(frames, pairs, strict=True)
    ]
    return sorted(found, key=lambda hit: (hit.frame, -hit.depth_m))


def _pairs(model: HandModel) -> tuple[np.ndarray, np.ndarray, np.ndarray, list[tuple[str, str]]]:
    """Return joint indices (n_pairs, 2) of both phalanges of every pair of different
    digits, their radius sums (n_pairs,) and their names."""
    segments = _segments(model)
    index = model.skeleton.index
    first, second, radii, names = [], [], [], []
    for i, (digit_i, a_i, b_i, r_i) in enumerate(segments):
        for digit_j, a_j, b_j, r_j in segments[i + 1 :]:
            if digit_i != digit_j:
                first.append((index(a_i), index(b_i)))
                second.append((index(a_j), index(b_j)))
                radii.append(r_i + r_j)
                names.append((f"{a_i}–{b_i}", f"{a_j}–{b_j}"))
    return np.array(first), np.array(second), np.array(radii), names


def _line_sides(positions: np.ndarray, first: np.ndarray, second: np.ndarray):
    """Return the signed distance (n_frames, n_pairs) between each pair's axis lines and
    whether their closest points lie inside both segments."""
    p1, q1 = positions[:, first[:, 0]], positions[:, first[:, 1]]
    p2, q2 = positions[:, second[:, 0]], positions[:, second[:, 1]]
    d1, d2, r = q1 - p1, q2 - p2, p1 - p2
    normal = np.cross(d1, d2)
    length = np.linalg.norm(normal, axis=-1)
    a, e, b = np.sum(d1 * d1, -1), np.sum(d2 * d2, -1), np.sum(d1 * d2, -1)
    c, f = np.sum(d1 * r, -1), np.sum(d2 * r, -1)
    denominator = np.maximum(a * e - b * b, 1e-18)
    s = (b * f - c * e) / denominator
    t = (a * f - b * c) / denominator
    signed = np.sum(r * normal, -1) / np.maximum(length, 1e-12)
    inside = (s > 0) & (s < 1) & (t > 0) & (t < 1) & (length > 1e-9)
    return signed, inside


def finger_crossings(model: HandModel, dofs_rad: np.ndarray) -> list[Crossing]:
    """Return every pass of one digit's phalanx through another's over the frames.

    Frames must be close enough that no phalanx jumps past another between two of them
    (a few degrees apart: a 60 fps clip, or a path sampled as finely).
    """
    first, second, radii, names = _pairs(model)
    positions = model.pose(np.atleast_2d(dofs_rad)).positions_m
    signed, inside = _line_sides(positions, first, second)
    # Only a sign change where the axes are close is a meeting of the lines: far apart,
    # the sign also flips when the two segments turn parallel.
    near = inside & (np.abs(signed) < radii)
    flips = (np.sign(signed[1:]) != np.sign(signed[:-1])) & (near[1:] | near[:-1])
    flips &= inside[1:] & inside[:-1]
    frames, pairs = np.nonzero(flips)
    return [Crossing(int(f) + 1, *names[p]) for f, p in zip(frames, pairs, strict=True)]


def overlap_depths_m(model: HandModel, dofs_rad: np.ndarray) -> np.ndarray:
    """Return the capsule overlap (n_frames, n_pairs) of every pair of digits' phalanges,
    negative where they are apart (m)."""
    first, second, radii, _ = _pairs(model)
    positions = model.pose(np.atleast_2d(dofs_rad)).positions_m
    distance = segment_distances(
        positions[:, first[:, 0]],
        positions[:, first[:, 1]],
        positions[:, second[:, 0]],
        positions[:, second[:, 1]],
    )
    return radii - distance
