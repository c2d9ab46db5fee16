"""Move MakeHuman's shaped mesh onto the engine's skeleton at its bind pose.

Each MakeHuman bone gets a transform; a vertex moves by the blend of its bones'
transforms with MakeHuman's skin weights, ``v' = Σ w_b T_b(v)`` (the blend that also
animates it, so the seams the warp leaves are those skinning would). An arm or hand
bone's transform takes its MakeHuman segment onto the engine's: the segment's start onto
the engine joint, stretched along the segment to the engine's length, turned the little
that the bind-pose fit left between the two, and scaled across it by the region's
girth (*arm_girth*, *hand_girth*). A digit's bones map by their share of the digit's
length (:mod:`synthesis.avatar.human.fit`). The trunk and neck are scaled by height,
piecewise between three levels (pelvis, shoulders, eyes) at which MakeHuman's body meets
the engine's, and across by a scale that changes between them; the head is scaled
uniformly about the eyes, which land on the engine's.
"""

from dataclasses import dataclass

import numpy as np
from scipy.interpolate import interp1d
from scipy.spatial.transform import Rotation

from synthesis.avatar.human.fit import DIGITS, Correspondence, along_chain, chain_shares, unit


@dataclass(frozen=True)
class Affine:
    """``v ↦ target + linear · (v − origin)``."""

    origin: np.ndarray
    target: np.ndarray
    linear: np.ndarray

    def __call__(self, vertices_m: np.ndarray) -> np.ndarray:
        return self.target + (vertices_m - self.origin) @ self.linear.T


def segment_affine(start_mh, end_mh, start_e, end_e, girth: float) -> Affine:
    """Return the transform of MakeHuman's segment onto the engine's: start onto start,
    stretched along it to the engine's length, turned onto it by the least rotation, and
    scaled by *girth* across it."""
    u = unit(end_mh - start_mh)
    stretch = np.linalg.norm(end_e - start_e) / np.linalg.norm(end_mh - start_mh)
    scale = girth * np.eye(3) + (stretch - girth) * np.outer(u, u)
    turn, _ = Rotation.align_vectors([unit(end_e - start_e)], [u])
    return Affine(np.asarray(start_mh), np.asarray(start_e), turn.as_matrix() @ scale)


def frame_affine(frame_mh: np.ndarray, frame_e: np.ndarray, origin_mh, origin_e, scales) -> Affine:
    """Return the transform of one frame onto another (3×3 columns), scaling along the
    first frame's axes by *scales* (3,)."""
    return Affine(
        np.asarray(origin_mh), np.asarray(origin_e), frame_e @ np.diag(scales) @ frame_mh.T
    )


@dataclass(frozen=True)
class TrunkWarp:
    """The trunk and neck's warp: heights mapped piecewise linearly through *levels_mh* →
    *levels_e*; across, x and z scaled by *across* and z shifted by *shift* (m), each
    interpolated between the levels (held beyond them)."""

    levels_mh: np.ndarray
    levels_e: np.ndarray
    across: np.ndarray
    shift: np.ndarray

    def __call__(self, vertices_m: np.ndarray) -> np.ndarray:
        y = vertices_m[:, 1]
        # Heights beyond the levels go on along the end segments.
        height = interp1d(self.levels_mh, self.levels_e, fill_value="extrapolate")(y)
        across = np.interp(y, self.levels_mh, self.across)
        shift = np.interp(y, self.levels_mh, self.shift)
        return np.column_stack(
            [vertices_m[:, 0] * across, height, vertices_m[:, 2] * across + shift]
        )


def blend_warp(vertices_m: np.ndarray, bone_weights: dict, transforms: dict) -> np.ndarray:
    """Return ``Σ_b w_b T_b(v)`` for every vertex; *bone_weights* maps a bone to
    (indices, weights), *transforms* a bone to its T_b. Weights are normalised per vertex."""
    moved = np.zeros_like(vertices_m)
    total = np.zeros(len(vertices_m))
    for bone, (indices, weights) in bone_weights.items():
        moved[indices] += weights[:, None] * transforms[bone](vertices_m[indices])
        total[indices] += weights
    unweighted = total <= 0
    if unweighted.any():
        raise ValueError(f"{int(unweighted.sum())} vertices carry no bone weight.")
    return moved / total[:, None]


def digit_transforms(match: Correspondence, engine_points: dict, side: str, girth: float) -> dict:
    """Return each MakeHuman digit bone's transform onto the engine's chain (by share)."""
    suffix = {"right": ".R", "left": ".L"}[side]
    transforms = {}
    for digit, number in DIGITS.items():
        chain = match.chains[digit]
        shares = chain_shares(chain)
        engine_chain = np.array([engine_points[j] for j in match.digit_points[digit]])
        mapped = along_chain(engine_chain, shares)
        for k in range(3):
            transforms[f"finger{number}-{k + 1}{suffix}"] = segment_affine(
                chain[k], chain[k + 1], mapped[k], mapped[k + 1], girth
            )
    return transforms


def chain_position(vertices_m: np.ndarray, chain: np.ndarray) -> np.ndarray:
    """Return each vertex's share of a polyline's length at its nearest point on it."""
    shares = chain_shares(chain)
    best_distance = np.full(len(vertices_m), np.inf)
    best_share = np.zeros(len(vertices_m))
    for k in range(len(chain) - 1):
        start, end = chain[k], chain[k + 1]
        length = np.linalg.norm(end - start)
        t = np.clip((vertices_m - start) @ (end - start) / length**2, 0.0, 1.0)
        distance = np.linalg.norm(vertices_m - (start + np.outer(t, end - start)), axis=1)
        closer = distance < best_distance
        best_distance[closer] = distance[closer]
        best_share[closer] = (shares[k] + t * (shares[k + 1] - shares[k]))[closer]
    # Before the base (into the palm) the share goes on below 0.
    start, end = chain[0], chain[1]
    before = (
        (vertices_m - start)
        @ unit(end - start)
        / np.linalg.norm(np.diff(chain, axis=0), axis=1).sum()
    )
    return np.where(before < 0, before, best_share)
