"""Fill a gap between two signs with a stored transition, fitted in (seed 001 §3.6).

The stored curve is stretched to the gap's length and *skewed* so it starts on the
first sign's last value and ends on the second's first (Eq. 3.8; Hermite tangents Eq.
3.10; B-spline coefficients at their basis peaks Eq. 3.12). The ends then take the
signs' own slopes, averaged over W frames (Eq. 3.13–3.14): a Hermite curve's end
tangents turn and shorten by ``(π − Δθ)/π`` (Eq. 3.16), a B-spline's second and
second-to-last coefficients move (Eq. 3.17). The signs are never modified.
"""

import numpy as np
from scipy.interpolate import BSpline

from synthesis.transitions.baselines import linear_transition, simple_hermite_transition
from synthesis.transitions.database import StoredCurve, TransitionEntry
from synthesis.transitions.descriptor import gap_descriptor
from synthesis.transitions.hermite_fit import HermiteCurve
from synthesis.transitions.joins import join_bspline, join_tangent, window_tangent
from synthesis.transitions.skew import skew_bspline, skew_tangents, skew_values

BASELINES = ("linear", "simple_hermite")
MODELS = (*BASELINES, "hermite", "bspline")
MODEL_LABELS = {
    "linear": "linear",
    "simple_hermite": "simple Hermite",
    "hermite": "Hermite (data-driven)",
    "bspline": "B-spline (data-driven)",
}
WINDOW_FRAMES = 4


def skewed_hermite(curve: StoredCurve, v0: float, v1: float, duration: float) -> HermiteCurve:
    """Return a stored Hermite curve stretched over *duration* frames and skewed to v0, v1."""
    h = curve.hermite
    y0, y_n = h.points[0, 1], h.points[-1, 1]
    points = np.column_stack(
        [
            h.points[:, 0] * duration,
            skew_values(h.points[:, 1], h.points[:, 0], curve.delta_rad, v0, v1),
        ]
    )
    t0 = skew_tangents(h.t0, y0, y_n, curve.delta_rad, v0, v1, duration)
    t1 = skew_tangents(h.t1, y0, y_n, curve.delta_rad, v0, v1, duration)
    return HermiteCurve(points, t0, t1)


def joined(curve: HermiteCurve, slope_in: float, slope_out: float) -> HermiteCurve:
    """Return *curve* with its end tangents turned to the signs' slopes (Eq. 3.16)."""
    t0, t1 = curve.t0.copy(), curve.t1.copy()
    # Each end segment moves forward in time while its two tangents' time extents add up
    # to at most three times its own (Fritsch–Carlson): the turned one gets what the
    # other leaves.
    first, last = np.diff(curve.points[:2, 0])[0], np.diff(curve.points[-2:, 0])[0]
    room_in = max(0.0, 3.0 * first - max(curve.t1[0][0], 0.0))
    room_out = max(0.0, 3.0 * last - max(curve.t0[-1][0], 0.0))
    t0[0] = join_tangent(t0[0], slope_in, segment_frames=room_in)
    t1[-1] = join_tangent(t1[-1], slope_out, segment_frames=room_out)
    return HermiteCurve(curve.points, t0, t1)


def skewed_spline(curve: StoredCurve, v0: float, v1: float) -> BSpline:
    """Return a stored B-spline (normalized) in radians, its coefficients skewed (Eq. 3.12)."""
    spline = curve.spline
    count = len(spline.t) - spline.k - 1
    scaled = BSpline(spline.t, spline.c[:count] * curve.delta_rad, spline.k)
    return skew_bspline(scaled, v0, v1, curve.spline_peaks)


def slopes(before: np.ndarray, after: np.ndarray, window: int = WINDOW_FRAMES):
    """Return the signs' slopes at the joins (per frame), each (n_curves,) (Eq. 3.13–3.14)."""
    return window_tangent(before, window), -window_tangent(after[::-1], window)


def fit_entry(
    entry: TransitionEntry,
    before: np.ndarray,
    after: np.ndarray,
    n_frames: int,
    model: str = "hermite",
    window: int = WINDOW_FRAMES,
) -> np.ndarray:
    """Return *entry*'s transition fitted into a gap of *n_frames*, (n_frames, 7) rad.

    *before* (≥ W + 1, 7) ends on the first sign's last frame, *after* starts on the
    second's first; *model* ``hermite`` or ``bspline``.
    """
    duration = n_frames + 1
    frames = np.arange(1, n_frames + 1, dtype=float)
    slope_in, slope_out = slopes(before, after, window)
    out = np.empty((n_frames, len(entry.curves)))
    for c, curve in enumerate(entry.curves):
        v0, v1 = before[-1, c], after[0, c]
        if model == "hermite":
            hermite = joined(skewed_hermite(curve, v0, v1, duration), slope_in[c], slope_out[c])
            out[:, c] = hermite.evaluate(frames)
        elif model == "bspline":
            spline = join_bspline(skewed_spline(curve, v0, v1), slope_in[c], slope_out[c], duration)
            out[:, c] = spline(frames / duration)
        else:
            raise ValueError(f"A stored transition fits as 'hermite' or 'bspline', not {model!r}.")
    return out


def baseline(
    model: str, before: np.ndarray, after: np.ndarray, n_frames: int, window: int = WINDOW_FRAMES
) -> np.ndarray:
    """Return the linear or simple-Hermite transition of every curve, (n_frames, 7) rad."""
    if model == "linear":
        return np.column_stack(
            [
                linear_transition(before[-1, c], after[0, c], n_frames)
                for c in range(before.shape[1])
            ]
        )
    if model == "simple_hermite":
        slope_in, slope_out = slopes(before, after, window)
        return np.column_stack(
            [
                simple_hermite_transition(
                    before[-1, c], slope_in[c], after[0, c], slope_out[c], n_frames
                )
                for c in range(before.shape[1])
            ]
        )
    raise ValueError(f"Unknown baseline {model!r}: 'linear' or 'simple_hermite'.")


def transition(
    model: str,
    before: np.ndarray,
    after: np.ndarray,
    n_frames: int,
    search=None,
    exclude=(),
    descriptor: np.ndarray | None = None,
) -> tuple[np.ndarray, TransitionEntry | None]:
    """Return one arm's transition by *model* (:data:`MODELS`) and the entry it used.

    The data-driven models need a :class:`~synthesis.transitions.search.DescriptorSearch`;
    *exclude* keeps the query's own transition out (leave-one-out); *descriptor* is the
    gap's, when the caller has it at the database's frame rate (else it is computed
    from *before* and *after*).
    """
    if model not in MODELS:
        raise ValueError(f"Unknown transition model {model!r}; known: {', '.join(MODELS)}.")
    if model in BASELINES:
        return baseline(model, before, after, n_frames), None
    if search is None:
        raise ValueError(f"The {MODEL_LABELS[model]} model needs a transition database.")
    if descriptor is None:
        descriptor = gap_descriptor(before, after)
    index = search.nearest(descriptor, exclude)
    entry = search.database.entries[index]
    return fit_entry(entry, before, after, n_frames, model), entry
