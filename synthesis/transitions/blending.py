"""Concatenate recorded signs by overlapping each decay with the next attack (seed 004 §4.1.3).

Each sign is captured from and back to a rest pose; its first and last *a* frames
(attack and decay, 1 s in the seed) carry no meaning. Sign n + 1 starts *a* frames before
sign n ends, and across that overlap the pose is the weighted average
``(E'_n + a − t)/a · S_n + (t − E'_n)/a · S_{n+1}``: the weights run linearly from 1 to 0
and sum to 1. The seed prints ``E'_n = Σ D_i − a``; its piecewise definition, in which
sign n + 1 starts at E'_n, makes every overlap count, ``E'_n = Σ_{i≤n} D_i − n·a``.
Positions stay continuous but velocities jump at the overlap's ends (C⁰ only, the
"change of mind" the seed reports); :func:`velocity_jumps` measures it.
"""

import numpy as np


def blend_offsets(lengths, overlap: int) -> np.ndarray:
    """Return the frame at which each sign starts in the sequence (seed 004 §4.1.3).

    Sign n + 1 starts *overlap* frames before sign n ends: ``E'_n = Σ_{i≤n} D_i − n·a``.
    """
    lengths = np.asarray(lengths, dtype=int)
    if np.any(lengths < 2 * overlap):
        raise ValueError(
            f"Every sign needs at least {2 * overlap} frames: an attack and a "
            f"decay of {overlap} each."
        )
    return np.concatenate([[0], np.cumsum(lengths[:-1] - overlap)])


def blend_signs(signs, overlap: int) -> np.ndarray:
    """Return the signs concatenated with linear blending over *overlap* frames.

    *signs*: sequence of (n_frames_i, n_dofs) arrays (a standard rest pose at each end,
    seed 004 §3.1.3.4); returns (Σ n_i − (m − 1)·overlap, n_dofs). Within an overlap the
    weights are ``(k + 1)/(overlap + 1)`` for the incoming sign, k = 0 … overlap − 1.
    """
    signs = [np.asarray(sign, dtype=float) for sign in signs]
    if not signs:
        raise ValueError("Nothing to concatenate.")
    offsets = blend_offsets([len(s) for s in signs], overlap)
    total = int(offsets[-1] + len(signs[-1]))
    result = np.zeros((total, signs[0].shape[1]))
    weight = np.zeros(total)
    ramp = np.arange(1, overlap + 1) / (overlap + 1)
    for index, (start, sign) in enumerate(zip(offsets, signs, strict=True)):
        w = np.ones(len(sign))
        if index > 0 and overlap:
            w[:overlap] = ramp  # fades in over the previous sign's decay
        if index < len(signs) - 1 and overlap:
            w[-overlap:] = ramp[::-1]  # fades out under the next sign's attack
        result[start : start + len(sign)] += w[:, None] * sign
        weight[start : start + len(sign)] += w
    return result / weight[:, None]


def velocity_jumps(motion: np.ndarray, rate_hz: float) -> np.ndarray:
    """Return, per frame boundary, how much the velocity changes (rad/s per frame).

    The norm over DOFs of the second difference times the rate: a C¹ motion sampled
    finely changes little from frame to frame; linear blending shows spikes at the
    overlaps' ends. (n_frames, n_dofs) → (n_frames − 2,).
    """
    motion = np.asarray(motion, dtype=float)
    return np.linalg.norm(np.diff(motion, 2, axis=0), axis=1) * rate_hz
