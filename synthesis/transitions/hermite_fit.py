"""Fit a recorded curve with concatenated cubic Hermite segments (seed 001 App. A.1).

The curve is spliced at its local extrema (Eq. A.5) on a smoothed copy (the 5-tap
kernel of App. A.1.1), plateaus kept by their ends (Δy = range/100, Eq. A.6) and
crowded splice points merged (Δx). Each splice point's tangent takes the smoothed
curve's direction; each segment's two tangent lengths k0, k1 are found by brute force
over a grid from 0 to 5 segment lengths (Eq. A.8), keeping the pair with the lowest RMSE
whose curve is a function of time. Curves are in (frame, value); values in any unit.
"""

from dataclasses import dataclass

import numpy as np

from synthesis.transitions.baselines import hermite_points

SMOOTHING_KERNEL = np.array([0.1538, 0.1923, 0.3077, 0.1923, 0.1538])
SAMPLES = 48
# App. A.1.2 tries 100 tangent lengths from 0 to 5 × the segment's length, at each end.
TANGENT_STEPS = 100
# Their 100 × 100 pairs are searched coarse to fine: every 4th length, then around the best.
COARSE_STRIDE = 4


@dataclass(frozen=True)
class HermiteCurve:
    """Concatenated cubic Hermite segments in (x, y): *points* (m + 1, 2) the splice points,
    *t0* and *t1* (m, 2) each segment's start and end tangents (Eq. A.2)."""

    points: np.ndarray
    t0: np.ndarray
    t1: np.ndarray

    def evaluate(self, x: np.ndarray, samples: int = SAMPLES) -> np.ndarray:
        """Return the curve's values at *x* (within its span), reading each segment densely."""
        s = np.linspace(0.0, 1.0, samples)
        pieces = [
            hermite_points(self.points[i], self.points[i + 1], self.t0[i], self.t1[i], s)
            for i in range(len(self.t0))
        ]
        dense = np.vstack(pieces)
        order = np.argsort(dense[:, 0], kind="stable")
        return np.interp(np.asarray(x, dtype=float), dense[order, 0], dense[order, 1])

    def to_dict(self) -> dict:
        """Return the segments as the seed's XML holds them: p0, t0, p1, t1 per segment."""
        return {
            "segments": [
                {
                    "p0": _round(self.points[i]),
                    "t0": _round(self.t0[i]),
                    "p1": _round(self.points[i + 1]),
                    "t1": _round(self.t1[i]),
                }
                for i in range(len(self.t0))
            ]
        }

    @classmethod
    def from_dict(cls, data: dict) -> "HermiteCurve":
        """Return the curve :meth:`to_dict` wrote; raise ValueError on a malformed one."""
        segments = data["segments"]
        if not segments:
            raise ValueError("A Hermite curve needs at least one segment.")
        points = [segments[0]["p0"]] + [seg["p1"] for seg in segments]
        arrays = [
            np.array(v, dtype=float)
            for v in (points, [s["t0"] for s in segments], [s["t1"] for s in segments])
        ]
        if any(a.ndim != 2 or a.shape[1] != 2 for a in arrays):
            raise ValueError("Hermite points and tangents are pairs [x, y].")
        return cls(*arrays)


def _round(values) -> list[float]:
    return [round(float(v), 7) for v in values]


def smooth(values: np.ndarray) -> np.ndarray:
    """Return *values* filtered by App. A.1.1's 5-tap kernel (ends repeated)."""
    padded = np.pad(np.asarray(values, dtype=float), 2, mode="edge")
    return np.convolve(padded, SMOOTHING_KERNEL / SMOOTHING_KERNEL.sum(), mode="valid")


def splice_points(values: np.ndarray, min_gap: int) -> np.ndarray:
    """Return the frames to splice a curve at (Eq. A.5–A.6), its ends included.

    Candidates are the extrema ``(y_i − y_{i−1})(y_{i+1} − y_i) ≤ 0``; a run of
    candidates within Δy = range/100 of each other (a plateau) keeps its first and last;
    candidates closer than *min_gap* frames (noise) merge into their mean.
    """
    y = np.asarray(values, dtype=float)
    n = len(y)
    delta_y = (y.max() - y.min()) / 100
    d = np.diff(y)
    candidates = list(np.flatnonzero(d[:-1] * d[1:] <= 0) + 1)
    kept, run = [], []
    for i in candidates:
        if run and abs(y[i] - y[run[0]]) <= delta_y and i - run[-1] <= min_gap:
            run.append(i)
            continue
        if run:
            kept += sorted({run[0], run[-1]})
        run = [i]
    if run:
        kept += sorted({run[0], run[-1]})
    merged: list[list[int]] = []
    for i in kept:
        if merged and i - merged[-1][-1] < min_gap:
            merged[-1].append(i)
        else:
            merged.append([i])
    inner = [round(np.mean(group)) for group in merged]
    frames = [0] + [i for i in inner if min_gap <= i <= n - 1 - min_gap] + [n - 1]
    return np.array(sorted(set(frames)))


def _directions(smoothed: np.ndarray, frames: np.ndarray) -> np.ndarray:
    """Return unit tangents (len(frames), 2) along the smoothed curve at *frames*."""
    slope = np.gradient(smoothed)[frames]
    return np.column_stack([np.ones_like(slope), slope]) / np.hypot(1.0, slope)[:, None]


def grid_rmse(
    x: np.ndarray, y: np.ndarray, d0: np.ndarray, d1: np.ndarray, k0: np.ndarray, k1: np.ndarray
) -> np.ndarray:
    """Return the RMSE of the segment drawn with every tangent length pair (len(k0), len(k1)).

    Eq. A.8's curve, sampled densely, is read at the segment's frames; a pair whose
    curve turns back in time (not a function of time) gets infinity.
    """
    s = np.linspace(0.0, 1.0, SAMPLES)
    h00, h10, h01, h11 = (
        2 * s**3 - 3 * s**2 + 1,
        s**3 - 2 * s**2 + s,
        -2 * s**3 + 3 * s**2,
        s**3 - s**2,
    )
    a, b = np.asarray(k0, dtype=float)[:, None, None], np.asarray(k1, dtype=float)[None, :, None]
    cx = h00 * x[0] + h10 * a * d0[0] + h01 * x[-1] + h11 * b * d1[0]
    cy = h00 * y[0] + h10 * a * d0[1] + h01 * y[-1] + h11 * b * d1[1]
    cx, cy = cx.reshape(-1, SAMPLES), cy.reshape(-1, SAMPLES)
    rmse = np.full(len(cx), np.inf)
    valid = np.flatnonzero(np.all(np.diff(cx, axis=1) > 0, axis=1))
    cx, cy = cx[valid], cy[valid]
    # Each frame's place between the curve's dense samples, for every pair at once: the
    # pairs' (increasing) curves laid end to end, each shifted past the one before, are
    # one sorted array to search.
    span = 2.0 * (np.abs(cx).max() + np.abs(x).max() + 1.0)
    rows = np.arange(len(cx))[:, None]
    found = np.searchsorted(
        (cx + rows * span).ravel(), (x[None, :] + rows * span).ravel(), side="right"
    ).reshape(len(cx), -1)
    index = np.clip(found - 1 - rows * SAMPLES, 0, SAMPLES - 2)
    xa, xb = cx[rows, index], cx[rows, index + 1]
    ya, yb = cy[rows, index], cy[rows, index + 1]
    w = np.clip(np.divide(x[None, :] - xa, xb - xa, out=np.zeros_like(xa), where=xb > xa), 0, 1)
    rmse[valid] = np.sqrt(np.mean((ya + w * (yb - ya) - y[None, :]) ** 2, axis=1))
    return rmse.reshape(len(k0), len(k1))


def fit_segment(
    x: np.ndarray,
    y: np.ndarray,
    d0: np.ndarray,
    d1: np.ndarray,
    steps: int = TANGENT_STEPS,
    coarse: int = COARSE_STRIDE,
) -> tuple[np.ndarray, np.ndarray, float]:
    """Return the tangents (t0, t1) and RMSE of one segment's best fit (Eq. A.8–A.11).

    *x*, *y*: the segment's samples, first and last being its ends; *d0*, *d1*: unit
    tangent directions. Lengths k0, k1 run over *steps* values from 0 to 5 × the
    segment's length (App. A.1.2: 100). The grid is searched coarse to fine: every
    *coarse*-th length first, then every length within *coarse* steps of the best pair
    (``coarse=1`` tries all steps² pairs; the two agree on the fits the database makes,
    bench/bench_transitions.py).
    """
    k = np.linspace(0.0, 5.0 * (x[-1] - x[0]), steps)
    rough = np.unique(np.r_[np.arange(0, steps, max(coarse, 1)), steps - 1])
    errors = grid_rmse(x, y, d0, d1, k[rough], k[rough])
    i, j = np.unravel_index(int(np.argmin(errors)), errors.shape)
    if coarse > 1:
        near_i = np.arange(max(rough[i] - coarse, 0), min(rough[i] + coarse, steps - 1) + 1)
        near_j = np.arange(max(rough[j] - coarse, 0), min(rough[j] + coarse, steps - 1) + 1)
        errors = grid_rmse(x, y, d0, d1, k[near_i], k[near_j])
        a, b = np.unravel_index(int(np.argmin(errors)), errors.shape)
        i, j = near_i[a], near_j[b]
    else:
        i, j = rough[i], rough[j]
    return k[i] * d0, k[j] * d1, float(errors.min())


def fit_hermite(
    values: np.ndarray, min_gap: int | None = None, steps: int = TANGENT_STEPS
) -> HermiteCurve:
    """Return concatenated Hermite segments fitted to *values* over frames 0 … n − 1."""
    y = np.asarray(values, dtype=float)
    if len(y) < 2:
        raise ValueError("A curve to fit needs at least 2 frames.")
    min_gap = min_gap or max(3, len(y) // 8)
    smoothed = smooth(y)
    frames = splice_points(smoothed, min_gap)
    directions = _directions(smoothed, frames)
    points = np.column_stack([frames.astype(float), y[frames]])
    t0, t1 = [], []
    for a, b, d0, d1 in zip(frames[:-1], frames[1:], directions[:-1], directions[1:], strict=True):
        x = np.arange(a, b + 1, dtype=float)
        first, last, _ = fit_segment(x, y[a : b + 1], d0, d1, steps)
        t0.append(first)
        t1.append(last)
    return HermiteCurve(points, np.array(t0), np.array(t1))
