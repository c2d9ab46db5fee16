"""Forward kinematics: global joint transforms from a motion (seed 004 §4.2.1).

Convention, stated once for the whole engine: column vectors, right-multiplied local
transforms. A joint's global rotation is ``G_i = G_parent(i) · L_i`` and its global
position ``p_i = p_parent(i) + G_parent(i) · t_i``, where ``L_i`` is its local rotation
(:meth:`Motion.local_rotations`) and ``t_i`` its translation from the parent (rest
offset plus position channels, in metres). Seed 004 writes the same product in the
row-vector convention as ``G_i = L_i · G_p(i)``.
"""

from dataclasses import dataclass

import numpy as np

from synthesis.skeleton.motion import Motion
from synthesis.skeleton.rotations import quat_conjugate, quat_multiply, quat_rotate, quat_to_matrix
from synthesis.skeleton.skeleton import Skeleton


@dataclass(frozen=True)
class Pose:
    """Global joint transforms: quaternions (..., n_joints, 4), positions (..., n_joints, 3) m."""

    quaternions: np.ndarray
    positions_m: np.ndarray

    @property
    def rotations(self) -> np.ndarray:
        """Return the global rotation matrices, shape (..., n_joints, 3, 3)."""
        return quat_to_matrix(self.quaternions)


def forward_kinematics_arrays(
    skeleton: Skeleton, local_quaternions: np.ndarray, local_translations_m: np.ndarray
) -> Pose:
    """Compose local transforms into global ones, vectorised over frames.

    *local_quaternions* is (n_frames, n_joints, 4), *local_translations_m* is
    (n_frames, n_joints, 3). Joints of one tree depth are composed in one batched
    product, so the Python loop runs over depth levels only.
    """
    parents = skeleton.parents
    # Joint-major layout: gathering a level's parents copies contiguous blocks.
    local_q = np.ascontiguousarray(np.swapaxes(local_quaternions, 0, 1))
    local_t = np.ascontiguousarray(np.swapaxes(local_translations_m, 0, 1))
    rotations = np.empty_like(local_q)
    positions = np.empty_like(local_t)
    for level in skeleton.depth_levels():
        roots = level[parents[level] < 0]
        inner = level[parents[level] >= 0]
        if roots.size:
            rotations[roots] = local_q[roots]
            positions[roots] = local_t[roots]
        if inner.size:
            parent_rotations = rotations[parents[inner]]
            rotations[inner] = quat_multiply(parent_rotations, local_q[inner])
            positions[inner] = positions[parents[inner]] + quat_rotate(
                parent_rotations, local_t[inner]
            )
    return Pose(quaternions=np.swapaxes(rotations, 0, 1), positions_m=np.swapaxes(positions, 0, 1))


def local_transforms(parents: np.ndarray, pose: Pose) -> tuple[np.ndarray, np.ndarray]:
    """Return each joint's rotation and translation in its parent's frame, (…, n, 4) and
    (…, n, 3), from global ones: the inverse of :func:`forward_kinematics_arrays` (a
    root's are its global ones)."""
    q, p = np.asarray(pose.quaternions, float), np.asarray(pose.positions_m, float)
    inner = parents >= 0
    local_q, local_t = q.copy(), p.copy()
    parent_q = quat_conjugate(q[..., parents[inner], :])
    local_q[..., inner, :] = quat_multiply(parent_q, q[..., inner, :])
    local_t[..., inner, :] = quat_rotate(parent_q, p[..., inner, :] - p[..., parents[inner], :])
    return local_q, local_t


def forward_kinematics(motion: Motion) -> Pose:
    """Return every joint's global rotation and position for every frame of *motion*."""
    return forward_kinematics_arrays(
        motion.skeleton, motion.local_quaternions(), motion.local_translations_m()
    )
