"""A rig: a skeleton whose joints turn by named degrees of freedom within limits.

Subclasses (the hand model, the upper-body model) describe their joints and DOFs; this
base turns DOF vectors into local rotations, global transforms and BVH channel values.
Each joint's local rotation is its fixed rest rotation followed by its DOFs as ZXY
Euler angles, so every bone can lie along its joint's local +y.
"""

from dataclasses import dataclass
from functools import cached_property

import numpy as np
from scipy.spatial.transform import Rotation

from synthesis.skeleton.kinematics import Pose, forward_kinematics_arrays
from synthesis.skeleton.motion import Motion
from synthesis.skeleton.rotations import euler_angles, quat_from_euler, quat_multiply
from synthesis.skeleton.skeleton import Joint, Skeleton

_EULER_COLUMN = {"z": 0, "x": 1, "y": 2}


@dataclass(frozen=True)
class Dof:
    """One degree of freedom: which joint, which local axis, sign, limits (degrees)."""

    name: str
    joint: str
    axis: str
    sign: float
    min_deg: float
    max_deg: float
    literature: str


@dataclass(frozen=True)
class JointSpec:
    """One joint of a rig: parent, offset in the parent's frame (m), rest rotation."""

    name: str
    parent: str
    offset_m: tuple[float, float, float]
    rest_rotation: np.ndarray | None = None
    is_end: bool = False


class Rig:
    """Base of the hand and body models; subclasses define ``dofs`` and ``joint_specs``."""

    dofs: tuple[Dof, ...]
    joint_specs: tuple[JointSpec, ...]
    # What error messages call the rig ("Unknown hand DOF …").
    kind = "rig"

    @cached_property
    def dof_names(self) -> list[str]:
        return [dof.name for dof in self.dofs]

    @cached_property
    def literature_names(self) -> list[str]:
        return [dof.literature for dof in self.dofs]

    @cached_property
    def limits_rad(self) -> tuple[np.ndarray, np.ndarray]:
        """Return the lower and upper limit of every DOF, radians."""
        return (
            np.radians([dof.min_deg for dof in self.dofs]),
            np.radians([dof.max_deg for dof in self.dofs]),
        )

    @cached_property
    def skeleton(self) -> Skeleton:
        """Return the rig as a BVH skeleton (metres; ZXY rotation channels)."""
        names = [spec.name for spec in self.joint_specs]
        joints = tuple(
            Joint(
                spec.name,
                names.index(spec.parent) if spec.parent else -1,
                tuple(float(v) for v in spec.offset_m),
                () if spec.is_end else ("Zrotation", "Xrotation", "Yrotation"),
                is_end_site=spec.is_end,
            )
            for spec in self.joint_specs
        )
        return Skeleton(joints, length_unit="m")

    def clip(self, dofs_rad: np.ndarray) -> np.ndarray:
        """Return the DOF values clamped to the joint limits."""
        low, high = self.limits_rad
        return np.clip(dofs_rad, low, high)

    def neutral(self) -> np.ndarray:
        """Return the all-zero pose."""
        return np.zeros(len(self.dofs))

    def from_degrees(self, angles_deg: dict[str, float]) -> np.ndarray:
        """Return a DOF vector (radians) from DOF names (or literature names) in degrees."""
        values = self.neutral()
        lookup = {dof.name: i for i, dof in enumerate(self.dofs)}
        lookup.update({dof.literature: i for i, dof in enumerate(self.dofs)})
        for name, angle in angles_deg.items():
            if name not in lookup:
                raise KeyError(f"Unknown {self.kind} DOF {name!r}.")
            values[lookup[name]] = np.radians(angle)
        return values

    @cached_property
    def _angle_map(self) -> tuple[np.ndarray, np.ndarray]:
        """Return (n_dofs, n_joints·3) DOF → ZXY-angle matrix and (n_joints, 4) rest quaternions."""
        names = [spec.name for spec in self.joint_specs]
        matrix = np.zeros((len(self.dofs), len(names) * 3))
        for i, dof in enumerate(self.dofs):
            matrix[i, names.index(dof.joint) * 3 + _EULER_COLUMN[dof.axis]] = dof.sign
        rest_q = np.zeros((len(names), 4))
        rest_q[:, 3] = 1.0
        for k, spec in enumerate(self.joint_specs):
            if spec.rest_rotation is not None:
                rest_q[k] = Rotation.from_matrix(spec.rest_rotation).as_quat()
        return matrix, rest_q

    def local_quaternions(self, dofs_rad: np.ndarray) -> np.ndarray:
        """Return each joint's local rotation, (..., n_dofs) → (..., n_joints, 4) quaternions."""
        dofs_rad = np.asarray(dofs_rad, dtype=np.float64)
        matrix, rest_q = self._angle_map
        angles = (dofs_rad @ matrix).reshape(*dofs_rad.shape[:-1], len(rest_q), 3)
        return quat_multiply(rest_q, quat_from_euler(angles, "ZXY"))

    def pose(self, dofs_rad: np.ndarray, bone_scale: np.ndarray | None = None) -> Pose:
        """Return global joint transforms for DOF vectors, shape (n_frames, n_dofs) or (n_dofs,).

        *bone_scale* (n_joints,) lengthens each joint's offset from its parent (a
        signer's own proportions); None keeps the rig's.
        """
        dofs_rad = np.atleast_2d(dofs_rad)
        skeleton = self.skeleton
        offsets = skeleton.offsets * skeleton.metres_per_unit
        if bone_scale is not None:
            offsets = offsets * np.asarray(bone_scale, dtype=np.float64)[:, None]
        translations = np.broadcast_to(offsets, (dofs_rad.shape[0], len(skeleton), 3))
        return forward_kinematics_arrays(skeleton, self.local_quaternions(dofs_rad), translations)

    def channel_values(self, dofs_rad: np.ndarray) -> np.ndarray:
        """Return BVH channel values (degrees, ZXY per joint) for DOF vectors (n_frames, n_dofs)."""
        quaternions = self.local_quaternions(np.atleast_2d(dofs_rad))
        with_channels = [i for i, joint in enumerate(self.skeleton.joints) if joint.channels]
        rotations = Rotation.from_quat(quaternions[:, with_channels].reshape(-1, 4))
        angles = euler_angles(rotations, "ZXY", degrees=True)
        return angles.reshape(quaternions.shape[0], -1)

    def as_motion(self, dofs_rad: np.ndarray, rate_hz: float) -> Motion:
        """Return DOF vectors (n_frames, n_dofs) sampled at *rate_hz* as a BVH-ready Motion."""
        return Motion(self.skeleton, self.channel_values(dofs_rad), 1.0 / rate_hz)

    def dofs_from_motion(self, motion: Motion) -> np.ndarray:
        """Return the DOF vectors (n_frames, n_dofs) of a motion of this rig's skeleton.

        The inverse of :meth:`as_motion`: each joint's rotation relative to its rest is
        read back as ZXY angles, and each DOF takes its joint's angle about its axis.
        Raise ValueError when *motion* is of another skeleton.
        """
        # End sites carry no channels and BVH names them after their parent.
        mine = [joint.name for joint in self.skeleton.joints if joint.channels]
        theirs = [joint.name for joint in motion.skeleton.joints if joint.channels]
        if mine != theirs:
            raise ValueError(
                f"The motion is not of the {self.kind} skeleton (its joints are "
                f"{', '.join(theirs[:4])}…; expected {', '.join(mine[:4])}…)."
            )
        matrix, rest_q = self._angle_map
        rest = Rotation.from_quat(
            np.broadcast_to(rest_q, (motion.n_frames, *rest_q.shape)).reshape(-1, 4)
        )
        local = Rotation.from_quat(motion.local_quaternions().reshape(-1, 4))
        angles = euler_angles(rest.inv() * local, "ZXY").reshape(motion.n_frames, -1, 3)
        # ZXY angles name each rotation twice, (z, x, y) and (z + π, π − x, y + π); the
        # decomposition keeps |x| ≤ 90°, but a finger flexes further. Take the smaller.
        other = np.stack(
            [angles[..., 0] + np.pi, np.pi - angles[..., 1], angles[..., 2] + np.pi], axis=-1
        )
        other = (other + np.pi) % (2 * np.pi) - np.pi
        smaller = np.abs(other).sum(axis=-1) < np.abs(angles).sum(axis=-1)
        angles = np.where(smaller[..., None], other, angles)
        return angles.reshape(motion.n_frames, -1) @ matrix.T


def mirror_dof(dof: Dof) -> Dof:
    """Return a DOF for the mirror image (x ↦ −x): rotations about y and z change sign."""
    sign = dof.sign if dof.axis == "x" else -dof.sign
    return Dof(dof.name, dof.joint, dof.axis, sign, dof.min_deg, dof.max_deg, dof.literature)


MIRROR_X = np.diag([-1.0, 1.0, 1.0])
