"""Skinning: bone weights for a rest mesh, and linear blend skinning over frames.

``v' = Σ_j w_ij · G_j · B_j⁻¹ · v`` (seed 004 §4.2.2), with at most four bones a vertex
and weights that sum to one. ``B_j`` is joint j's global transform at the rest (bind)
pose, ``G_j`` the posed one; both come from the engine's forward kinematics.
"""

from dataclasses import dataclass

import numpy as np
from scipy import sparse

from synthesis.skeleton.kinematics import Pose
from synthesis.skeleton.rotations import quat_to_matrix

MAX_BONES = 4


@dataclass(frozen=True)
class SkinWeights:
    """Per-vertex bone indices (n, 4) and weights (n, 4); unused slots have weight 0."""

    joints: np.ndarray
    weights: np.ndarray
    main: np.ndarray | None = None  # each vertex's main joint, where a file says it

    def main_joints(self) -> np.ndarray:
        """Return each vertex's joint of largest weight (n,): the slot of largest weight
        (a joint listed in two slots counts by one of them), or *main* where given (an
        imported engine avatar keeps the engine's, which framing follows)."""
        if self.main is not None:
            return self.main
        return self.joints[np.arange(len(self.joints)), np.argmax(self.weights, axis=1)]

    def matrix(self, n_joints: int) -> sparse.csr_matrix:
        """Return the weights as a sparse (n_vertices, n_joints) matrix."""
        n = len(self.joints)
        rows = np.repeat(np.arange(n), self.joints.shape[1])
        return sparse.csr_matrix(
            (self.weights.ravel(), (rows, self.joints.ravel())), shape=(n, n_joints)
        )


def skin_weights(
    vertices_m: np.ndarray,
    primitives,
    joint_index: dict[str, int],
    power: float = 8.0,
) -> SkinWeights:
    """Weight each vertex by its closeness to the bones, relative to each bone's thickness.

    A bone's closeness is the distance to its axis divided by its radius there, so a
    vertex on a finger sits at about 1 from its own phalanx, and weights cross over at
    the joint between two phalanges; ``power`` sets how quickly (8: over about one
    finger radius either side of the joint). The four largest weights are kept.
    """
    owners = sorted({p.joint for p in primitives}, key=lambda name: joint_index[name])
    scores = np.full((len(vertices_m), len(owners)), np.inf)
    for primitive in primitives:
        column = owners.index(primitive.joint)
        scores[:, column] = np.minimum(
            scores[:, column], primitive.relative_axis_distance(vertices_m)
        )
    top, weights = strongest_weights((scores + 0.05) ** -power)
    joints = np.array([joint_index[name] for name in owners])[top]
    return SkinWeights(joints=joints.astype(np.intp), weights=weights)


def strongest_weights(dense: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Return each vertex's :data:`MAX_BONES` largest weights of *dense* (n, columns):
    their columns and the weights, normalised to sum to one."""
    top = np.argsort(-dense, axis=1)[:, :MAX_BONES]
    weights = np.take_along_axis(dense, top, axis=1)
    return top, weights / weights.sum(axis=1, keepdims=True)


def skin_transforms(pose: Pose, bind: Pose) -> np.ndarray:
    """Return per-joint skinning matrices ``G · B⁻¹`` as (n_frames, n_joints, 3, 4)."""
    rotations = quat_to_matrix(pose.quaternions)
    bind_rotations = quat_to_matrix(bind.quaternions)
    linear = rotations @ np.swapaxes(bind_rotations, -1, -2)
    translation = pose.positions_m - np.einsum("...ij,...j->...i", linear, bind.positions_m)
    return np.concatenate((linear, translation[..., None]), axis=-1)


def linear_blend_skinning(
    rest_vertices_m: np.ndarray,
    rest_normals: np.ndarray,
    weights: sparse.csr_matrix,
    transforms: np.ndarray,
) -> tuple[np.ndarray, np.ndarray]:
    """Deform a rest mesh: vertices and unit normals (n, 3) for each frame's transforms.

    *transforms* is (n_frames, n_joints, 3, 4) from :func:`skin_transforms`; returns
    (n_frames, n, 3) twice. The rest mesh is (n, 3), or (n_frames, n, 3) when it changes
    from frame to frame (blendshapes, :class:`Morphs`). Normals use the blended linear
    part, then are renormalised.
    """
    n_frames, n_joints = transforms.shape[:2]
    flat = np.moveaxis(transforms.reshape(n_frames, n_joints, 12), 0, 1).reshape(n_joints, -1)
    blended = np.moveaxis((weights @ flat).reshape(-1, n_frames, 3, 4), 1, 0)
    linear, translation = blended[..., :3], blended[..., 3]
    vertices = _times(linear, rest_vertices_m) + translation
    normals = _times(linear, rest_normals)
    normals /= np.linalg.norm(normals, axis=-1, keepdims=True)
    return vertices, normals


def _times(linear: np.ndarray, points: np.ndarray) -> np.ndarray:
    """Return ``linear @ point`` per frame and vertex: (f, n, 3, 3) by (n, 3) or (f, n, 3).

    Written out by columns: a third faster than einsum's (or matmul's) batched 3×3
    products at a batch of frames of a 10,000-vertex skin (bench/bench_render.py).
    """
    return (
        linear[..., 0] * points[..., 0:1]
        + linear[..., 1] * points[..., 1:2]
        + linear[..., 2] * points[..., 2:3]
    )


@dataclass(frozen=True, eq=False)
class Morphs:
    """A part's blendshapes at the bind pose: *names* (k,), the vertices they move (m,),
    and each one's offsets of those vertices and of their normals, (k, m, 3).

    A posed frame's rest mesh is ``v + Σ_k w_k Δv_k`` (its normals likewise, then
    renormalised), skinned as any rest mesh is.
    """

    names: tuple[str, ...]
    vertices: np.ndarray
    offsets_m: np.ndarray
    normal_offsets: np.ndarray

    def rest(
        self, vertices_m: np.ndarray, normals: np.ndarray, weights: np.ndarray
    ) -> tuple[np.ndarray, np.ndarray]:
        """Return each frame's rest vertices and normals (n_frames, n, 3) for blendshape
        *weights* (n_frames, k)."""
        n_frames = len(weights)
        moved = np.repeat(vertices_m[None], n_frames, axis=0)
        turned = np.repeat(normals[None], n_frames, axis=0)
        moved[:, self.vertices] += np.einsum("fk,kmi->fmi", weights, self.offsets_m)
        bent = turned[:, self.vertices] + np.einsum("fk,kmi->fmi", weights, self.normal_offsets)
        turned[:, self.vertices] = bent / np.linalg.norm(bent, axis=-1, keepdims=True)
        return moved, turned


@dataclass(frozen=True, eq=False)
class MorphDrive:
    """Blendshape weights from a rig's DOFs: ``w = clip(rising · max(d, 0) + falling ·
    max(−d, 0), 0, limits)`` with *rising* and *falling* (k, n_dofs) per radian, so a DOF
    can move one blendshape one way and another the other (a brow's raise and drop);
    *limits* (k,) the weight each blendshape may reach (1: its target; more extrapolates)."""

    names: tuple[str, ...]
    rising: np.ndarray
    falling: np.ndarray
    limits: np.ndarray

    def weights(self, dofs_rad: np.ndarray) -> np.ndarray:
        """Return the blendshape weights (n_frames, k) of DOF vectors (n_frames, n_dofs)."""
        dofs = np.atleast_2d(dofs_rad)
        raw = np.maximum(dofs, 0.0) @ self.rising.T + np.maximum(-dofs, 0.0) @ self.falling.T
        return np.clip(raw, 0.0, self.limits)
