"""Smooth random signals: Gaussian noise low-passed with a zero-phase Butterworth filter.

Used for the liveliness of held postures (synthesis.signing.liveliness, seed 003 §3.6) and for
simulated capture noise (synthesis.timing.simulate): coherent, band-limited wander in
the spirit of Perlin noise, deterministic for a given ``np.random.Generator``.
"""

import numpy as np
from scipy.signal import butter, sosfiltfilt


def band_limited_noise(
    n_frames: int, n_channels: int, cutoff_hz, rate_hz: float, rng: np.random.Generator
) -> np.ndarray:
    """Return unit-RMS noise (n_frames, n_channels) low-passed at *cutoff_hz*.

    *cutoff_hz* is one frequency or one per channel (n_channels,).
    """
    cutoffs = np.broadcast_to(np.asarray(cutoff_hz, dtype=float), (n_channels,))
    pad = int(rate_hz)  # room for the filter to settle at both ends
    white = rng.standard_normal((n_frames + 2 * pad, n_channels))
    out = np.empty((n_frames, n_channels))
    for cutoff in np.unique(cutoffs):
        columns = cutoffs == cutoff
        sos = butter(2, min(cutoff / (rate_hz / 2), 0.99), output="sos")
        out[:, columns] = sosfiltfilt(sos, white[:, columns], axis=0)[pad : pad + n_frames]
    return out / out.std(axis=0, keepdims=True).clip(1e-12)
