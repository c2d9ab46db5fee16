"""Convert colours between sRGB, as the engine keeps them, and linear, as glTF stores them.

glTF 2.0 (§3.7.2.1, §3.9.2) defines vertex colours and base colour factors as linear
values and colour textures as sRGB-encoded; the engine's avatar colours are display
sRGB values. The transfer function is IEC 61966-2-1's.
"""

import numpy as np


def srgb_to_linear(srgb: np.ndarray) -> np.ndarray:
    """Return linear values (0–1) of sRGB-encoded values (0–1), IEC 61966-2-1."""
    c = np.clip(np.asarray(srgb, dtype=float), 0.0, 1.0)
    return np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)


def linear_to_srgb(linear: np.ndarray) -> np.ndarray:
    """Return sRGB-encoded values (0–1) of linear values (0–1), IEC 61966-2-1."""
    c = np.clip(np.asarray(linear, dtype=float), 0.0, 1.0)
    return np.where(c <= 0.0031308, 12.92 * c, 1.055 * c ** (1 / 2.4) - 0.055)
