"""Match a transition's tangents to the signs' at the joins (seed 001 §3.6.2).

The signs are never modified: the transition's end tangents take the direction of the
signs' tangents, averaged over a window of W frames (Eq. 3.13–3.14), and their length
shrinks by ``(π − Δθ)/π`` (Eq. 3.16) so that a large turn does not overshoot.
"""

import numpy as np


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


def join_tangent(tangent: np.ndarray, sign_slope: float) -> np.ndarray:
    """Return *tangent* [t_x, t_y] turned to the sign's slope and shortened (Eq. 3.16).

    ``θ' = θ_sign`` and ``r' = r · (π − Δθ)/π``, Δθ the angle turned (rad): a tangent
    turned by a quarter turn keeps half its length, one already aligned keeps all.
    """
    t_x, t_y = np.asarray(tangent, dtype=float)
    r, theta = np.hypot(t_x, t_y), np.arctan2(t_y, t_x)
    theta_sign = np.arctan2(sign_slope, 1.0)
    turned = abs(theta_sign - theta)
    length = r * (np.pi - turned) / np.pi
    return np.array([length * np.cos(theta_sign), length * np.sin(theta_sign)])
