"""The baseline transitions seed 001 compares against (§4.1): linear and "simple Hermite".

A gap of *n* frames lies between a sign's last frame (value v0, at frame 0) and the
next sign's first frame (value v1, at frame n + 1); a transition gives the values of
frames 1 … n. Values are angles (rad) per frame.
"""

import numpy as np


def linear_transition(v0: float, v1: float, n_frames: int) -> np.ndarray:
    """Return the straight line from v0 to v1 over the *n_frames* of the gap."""
    return v0 + (v1 - v0) * np.arange(1, n_frames + 1) / (n_frames + 1)


def hermite_points(p0, p1, t0, t1, s: np.ndarray) -> np.ndarray:
    """Return the cubic Hermite curve at parameters *s* in [0, 1] (seed 001 Eq. 5.2).

    ``p(s) = (2s³ − 3s² + 1) p0 + (s³ − 2s² + s) t0 + (−2s³ + 3s²) p1 + (s³ − s²) t1``;
    points and tangents may be vectors (a 2-D curve of frame and value), *s*: (m,) →
    (m, d).
    """
    s = np.asarray(s, dtype=float)[:, None]
    p0, p1, t0, t1 = (np.atleast_1d(np.asarray(v, dtype=float)) for v in (p0, p1, t0, t1))
    return (
        (2 * s**3 - 3 * s**2 + 1) * p0
        + (s**3 - 2 * s**2 + s) * t0
        + (-2 * s**3 + 3 * s**2) * p1
        + (s**3 - s**2) * t1
    )


def _along(slope: float, length: float) -> np.ndarray:
    """Return the (frame, value) vector of *length* along a curve of *slope* per frame."""
    direction = np.array([1.0, slope]) / np.hypot(1.0, slope)
    return length * direction


def simple_hermite_transition(
    v0: float, slope0: float, v1: float, slope1: float, n_frames: int, samples: int = 512
) -> np.ndarray:
    """Return seed 001's *simple Hermite* over the gap's *n_frames* (§4.1).

    A 2-D Hermite curve in (frame, value) from the first sign's last frame to the second
    sign's first, its tangents half the gap's length (n + 1 frames) long and pointing
    along the signs' slopes there (*slope0*, *slope1*, value per frame). The curve is
    sampled densely and read at the whole frames 1 … n.
    """
    length = (n_frames + 1) / 2
    points = hermite_points(
        [0.0, v0],
        [n_frames + 1.0, v1],
        _along(slope0, length),
        _along(slope1, length),
        np.linspace(0, 1, samples),
    )
    frames, values = points[:, 0], points[:, 1]
    if np.any(np.diff(frames) <= 0):
        raise ValueError("The signs' slopes turn the curve back in time; shorten them.")
    return np.interp(np.arange(1, n_frames + 1), frames, values)


def rmse_deg(original: np.ndarray, synthesized: np.ndarray) -> float:
    """Return the root-mean-square error in degrees of two curves in radians (Table 5.1)."""
    difference = np.degrees(np.asarray(original, float) - np.asarray(synthesized, float))
    return float(np.sqrt(np.mean(difference**2)))
