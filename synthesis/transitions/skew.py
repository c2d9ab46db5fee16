"""Fit a stored transition curve into a gap by skewing, not scaling (seed 001 §3.6.1).

A stored transition is normalized: time x in [0, 1], values y in [0, 1] (from its
minimum to its maximum), with ΔY its total amount of rotation. Skewing (Eq. 3.8) keeps
its shape and lands it exactly on the first sign's last value v0 and the second's first
value v1; scaling by Δv / Δy instead explodes when the curve ends where it started
(y_N ≈ y_0, seed 001 Fig. 4.3).
"""

import numpy as np
from scipy.interpolate import BSpline


def skew_values(
    y: np.ndarray, x: np.ndarray, delta_total: float, v0: float, v1: float
) -> np.ndarray:
    """Return ``y' = (y − y0)·ΔY + (Δv − (yN − y0)·ΔY)·x + v0`` (seed 001 Eq. 3.8).

    *y*: normalized values (n,), first y0 and last yN; *x*: normalized times (n,) from 0
    to 1; *delta_total*: ΔY, the stored curve's amount of rotation (rad); *v0*, *v1*: the
    signs' values at the joins (rad). The result starts at v0 and ends at v1 exactly.
    """
    y, x = np.asarray(y, dtype=float), np.asarray(x, dtype=float)
    y0, y_n = y[0], y[-1]
    return (y - y0) * delta_total + ((v1 - v0) - (y_n - y0) * delta_total) * x + v0


def skew_tangents(
    tangents: np.ndarray,
    y0: float,
    y_n: float,
    delta_total: float,
    v0: float,
    v1: float,
    duration: float,
) -> np.ndarray:
    """Return Hermite tangents [t_x, t_y] skewed like their curve (seed 001 Eq. 3.9–3.10).

    ``t_x' = t_x · t`` and ``t_y' = t_y·ΔY + (Δv − (yN − y0)·ΔY)·t_x``: the skew adds
    the same slope to every point, so a tangent gains it in proportion to its x extent
    (Eq. 3.10 prints the factor as *x*; the tangent's own t_x is what keeps the curve's
    derivative and its tangents equal). *tangents*: (n, 2) normalized; *duration*: t.
    """
    tangents = np.asarray(tangents, dtype=float)
    t_x, t_y = tangents[:, 0], tangents[:, 1]
    slope = (v1 - v0) - (y_n - y0) * delta_total
    return np.column_stack([t_x * duration, t_y * delta_total + slope * t_x])


def scale_values(y: np.ndarray, v0: float, v1: float) -> np.ndarray:
    """Return *y* scaled so it runs from v0 to v1: ``v0 + (y − y0)·Δv / (yN − y0)``.

    The alternative to skewing that seed 001 rejects: it divides by yN − y0, so a curve
    that returns to where it started is stretched without bound (Fig. 4.3).
    """
    y = np.asarray(y, dtype=float)
    return v0 + (y - y[0]) * (v1 - v0) / (y[-1] - y[0])


def basis_peaks(knots: np.ndarray, degree: int, samples: int = 4001) -> np.ndarray:
    """Return the x where each B-spline basis function peaks (seed 001 Eq. 3.11).

    The seed finds the zero of N'_{i,k} by bisection within the basis's support; here
    all basis functions are evaluated on a fine grid of the spline's domain and each
    peak is refined by a parabola through its best sample and the neighbours. With
    clamped knots the first and last peaks are the ends.
    """
    knots = np.asarray(knots, dtype=float)
    count = len(knots) - degree - 1
    x = np.linspace(knots[degree], knots[count], samples)
    values = BSpline(knots, np.eye(count), degree)(x)  # (samples, count)
    best = np.argmax(values, axis=0)
    inner = (best > 0) & (best < samples - 1)
    columns = np.arange(count)
    left = values[np.clip(best - 1, 0, samples - 1), columns]
    middle = values[best, columns]
    right = values[np.clip(best + 1, 0, samples - 1), columns]
    bend = left - 2 * middle + right
    shift = np.divide(0.5 * (left - right), bend, out=np.zeros(count), where=inner & (bend != 0))
    return x[best] + shift * (x[1] - x[0])


def skew_bspline(spline: BSpline, v0: float, v1: float, peaks: np.ndarray | None = None) -> BSpline:
    """Return *spline* with its coefficients skewed to run from v0 to v1 (Eq. 3.12).

    ``c_i' = (c_i − c_0) + (Δv − (c_N − c_0))·x_i + v0``, x_i the normalized position of
    the i-th basis function's peak. With clamped knots the curve passes through its
    first and last coefficients, so the result starts at v0 and ends at v1. *peaks*:
    :func:`basis_peaks` of the spline's knots, when the caller keeps them.
    """
    knots, degree = spline.t, spline.k
    count = len(knots) - degree - 1
    coefficients = np.asarray(spline.c[:count], dtype=float)
    peaks = basis_peaks(knots, degree) if peaks is None else peaks
    start, end = knots[degree], knots[count]
    x = (peaks - start) / (end - start)
    c0, c_n = coefficients[0], coefficients[-1]
    skewed = (coefficients - c0) + ((v1 - v0) - (c_n - c0)) * x + v0
    return BSpline(knots, skewed, degree)
