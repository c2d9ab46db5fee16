"""Match a transition's tangents to the signs' at the joins (seed 001 §3.6.2).

The signs are never modified: the transition's end tangents take the direction of the
signs' tangents, averaged over a window of W frames (Eq. 3.13–3.14). A Hermite
transition's end tangents shrink by ``(π − Δθ)/π`` (Eq. 3.16) so that a large turn does
not overshoot; a B-spline's second and second-to-last coefficients move so its ends
leave and arrive along the signs' slopes (Eq. 3.17).
"""

import numpy as np
from scipy.interpolate import BSpline

# Eq. 3.16 measures angles on the animation curve as seed 001 plots it (Maya's graph
# editor: frames across, degrees up). In radians every slope is nearly flat and the
# shrink never acts (a factor ≥ 0.998 on the built-in database, against 0.916 in degrees).
DEGREES_PER_UNIT = float(np.degrees(1.0))


def window_tangent(values: np.ndarray, window: int) -> float | np.ndarray:
    """Return the mean frame-to-frame slope of the last *window* + 1 *values* (per frame).

    Eq. 3.13–3.14 average the slope over W frames instead of taking the noisy last
    difference; pass the sign's frames nearest the join, ordered in time. *values*
    (n,) gives a number, (n, n_curves) one slope per curve.
    """
    values = np.asarray(values, dtype=float)
    if window < 1 or len(values) < window + 1:
        raise ValueError(f"A window of {window} frames needs {window + 1} values.")
    slope = np.mean(np.diff(values[-(window + 1) :], axis=0), axis=0)
    return float(slope) if slope.ndim == 0 else slope


def join_tangent(
    tangent: np.ndarray,
    sign_slope: float,
    degrees_per_unit: float = DEGREES_PER_UNIT,
    segment_frames: float | None = None,
) -> np.ndarray:
    """Return *tangent* [t_x, t_y] turned to the sign's slope and shortened (Eq. 3.16).

    ``θ' = θ_sign`` and ``r' = r · (π − Δθ)/π``, Δθ the angle turned: a tangent turned by
    a quarter turn keeps half its length, one already aligned keeps all. Angles and
    lengths are taken on the curve as seed 001 plots it, frames across and degrees up:
    *t_y* and *sign_slope* are in the curve's unit (rad, rad per frame), times
    *degrees_per_unit* (1 measures them in that unit itself).

    The turned tangent spans at most *segment_frames* in time: a steep tangent turned
    flat keeps its length in that plane and could reach far past its segment, so the
    curve ran backwards in time and the joint jumped (issue 53: 14 frames grew to 52 in a
    12-frame gap, 7,240 °/s). A cubic Hermite segment moves forward in time throughout
    while its two tangents' time extents add up to at most three times its own
    (Fritsch & Carlson 1980), which is what the caller leaves here.
    """
    t_x, t_y = np.asarray(tangent, dtype=float)
    up = t_y * degrees_per_unit
    r, theta = np.hypot(t_x, up), np.arctan2(up, t_x)
    theta_sign = np.arctan2(sign_slope * degrees_per_unit, 1.0)
    turned = abs(theta_sign - theta)
    length = r * (np.pi - turned) / np.pi
    if segment_frames is not None:
        length = min(length, segment_frames / np.cos(theta_sign))  # cos > 0: |θ| < π/2
    return np.array([length * np.cos(theta_sign), length * np.sin(theta_sign) / degrees_per_unit])


def join_bspline(spline: BSpline, slope_in: float, slope_out: float, duration: float) -> BSpline:
    """Return *spline* with c₂ and c_{N−1} moved so its end tangents are the signs' (Eq. 3.17).

    ``c₂' = c₁ + θ_in · t · x₂`` and ``c_{N−1}' = c_N − θ_out · t · x_{N−1}``: *slope_in*,
    *slope_out* (θ, per frame) the signs' slopes, *duration* t the gap in frames over the
    spline's normalized time, x the coefficient's distance from its end. The seed takes x
    from the basis functions' derivatives; here it is the Greville spacing
    ``(t_{k+1} − t_1)/k`` (and its mirror), with which a clamped spline's end derivative
    is the slope exactly. A spline of fewer than four coefficients is returned as it is:
    moving c₂ would move c_{N−1} too.
    """
    knots, degree = spline.t, spline.k
    count = len(knots) - degree - 1
    if count < 4:
        return spline
    c = np.array(spline.c[:count], dtype=float)
    start = (knots[degree + 1] - knots[1]) / degree
    end = (knots[count + degree - 1] - knots[count - 1]) / degree
    c[1] = c[0] + slope_in * duration * start
    c[-2] = c[-1] - slope_out * duration * end
    return BSpline(knots, c, degree)
