"""Describe a gap between two signs by the DCT-II of the frames around it (seed 001 §3.5).

For each of the arm curves, the last N = 10 frames before the gap and the first N after
it are each reduced to the coefficients k = 0, 1, 2 of the DCT-II
``X_k = Σ_n x_n cos(π/N (n + ½) k)``; with 7 curves that is 42 numbers.
"""

import numpy as np
from scipy.fft import dct

DESCRIPTOR_FRAMES = 10
DESCRIPTOR_COEFFICIENTS = 3


def dct_ii(values: np.ndarray, coefficients: int = DESCRIPTOR_COEFFICIENTS) -> np.ndarray:
    """Return the first DCT-II coefficients of *values* along axis 0 (seed 001 Eq. 3.4).

    ``X_k = Σ_n x_n cos(π/N (n + ½) k)``: scipy's unnormalized type-2 DCT is twice that.
    *values*: (N, ...) → (coefficients, ...).
    """
    values = np.asarray(values, dtype=float)
    return dct(values, type=2, axis=0)[:coefficients] / 2.0


def gap_descriptor(
    before: np.ndarray, after: np.ndarray, frames: int = DESCRIPTOR_FRAMES
) -> np.ndarray:
    """Return the descriptor of a gap: DCT-II of the *frames* before and after it.

    *before*: (n_before, n_curves) the first sign's curves, of which the last *frames*
    count; *after*: (n_after, n_curves) the second sign's, of which the first count.
    Returns (2 × 3 × n_curves,): for each curve its 3 coefficients before, then its 3
    after (curve-major, as the seed's XML stores ``in_dct00…out_dct02`` per curve).
    """
    before, after = np.asarray(before, dtype=float), np.asarray(after, dtype=float)
    if before.ndim != 2 or after.ndim != 2 or before.shape[1] != after.shape[1]:
        raise ValueError(
            f"before and after must be (frames, curves) with the same curves; got "
            f"{before.shape} and {after.shape}."
        )
    if len(before) < frames or len(after) < frames:
        raise ValueError(
            f"A descriptor needs {frames} frames on each side of the gap; got "
            f"{len(before)} before and {len(after)} after."
        )
    into = dct_ii(before[-frames:])  # (3, n_curves)
    out_of = dct_ii(after[:frames])
    return np.concatenate([into, out_of], axis=0).T.reshape(-1)
