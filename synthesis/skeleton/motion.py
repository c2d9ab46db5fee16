"""A motion: a skeleton's channel values over frames, at a fixed frame rate."""

from dataclasses import dataclass

import numpy as np

from synthesis.skeleton.rotations import quat_from_euler, quat_to_matrix
from synthesis.skeleton.skeleton import POSITION_CHANNELS, Skeleton


@dataclass(frozen=True, eq=False)
class Motion:
    """Channel values ``(n_frames, n_channels)`` for a skeleton, sampled every ``frame_time_s``.

    Values are kept as a BVH file holds them: positions in the skeleton's length unit,
    rotations in degrees in each joint's own Euler order. Use :meth:`local_rotations`
    and :meth:`root_positions_m` for computation (radians and metres inside).
    """

    skeleton: Skeleton
    values: np.ndarray
    frame_time_s: float

    def __post_init__(self) -> None:
        values = np.asarray(self.values, dtype=np.float64)
        if values.ndim != 2 or values.shape[1] != self.skeleton.channel_count:
            raise ValueError(
                f"Motion values must be (n_frames, {self.skeleton.channel_count}); "
                f"got {values.shape}."
            )
        if not np.all(np.isfinite(values)):
            raise ValueError("Motion values must be finite numbers.")
        if not (self.frame_time_s > 0 and np.isfinite(self.frame_time_s)):
            raise ValueError(f"Frame time must be positive; got {self.frame_time_s!r}.")
        values.setflags(write=False)
        object.__setattr__(self, "values", values)

    def __eq__(self, other: object) -> bool:
        """Compare exactly: same skeleton, frame time and bit-identical values."""
        if not isinstance(other, Motion):
            return NotImplemented
        return (
            self.skeleton == other.skeleton
            and self.frame_time_s == other.frame_time_s
            and self.values.shape == other.values.shape
            and bool(np.array_equal(self.values, other.values))
        )

    __hash__ = None  # type: ignore[assignment]  # equal by value, so unhashable

    @property
    def n_frames(self) -> int:
        return self.values.shape[0]

    @property
    def rate_hz(self) -> float:
        return 1.0 / self.frame_time_s

    @property
    def duration_s(self) -> float:
        """Return the time from the first to the last frame."""
        return (self.n_frames - 1) * self.frame_time_s

    @property
    def times_s(self) -> np.ndarray:
        """Return each frame's time, shape (n_frames,)."""
        return np.arange(self.n_frames) * self.frame_time_s

    def joint_values(self, name: str) -> np.ndarray:
        """Return one joint's channel values, shape (n_frames, n_joint_channels)."""
        index = self.skeleton.index(name)
        return self.values[:, self.skeleton.channel_slices()[index]]

    def local_quaternions(self) -> np.ndarray:
        """Return every joint's local rotation as a quaternion, shape (n_frames, n_joints, 4).

        Angles are applied in the joint's channel order as intrinsic rotations, so
        channels "Zrotation Xrotation Yrotation" give ``R = Rz · Rx · Ry`` (seed 004
        §4.2.1). Joints without rotation channels get the identity; missing axes are 0.
        """
        result = np.zeros((self.n_frames, len(self.skeleton), 4))
        result[..., 3] = 1.0
        # One vectorised conversion per Euler order covers every joint and frame at once.
        for order, (joints, columns) in self.skeleton.rotation_groups.items():
            angles = np.radians(self.values[:, columns]).reshape(self.n_frames, len(joints), -1)
            result[:, joints] = quat_from_euler(angles, order)
        return result

    def local_rotations(self) -> np.ndarray:
        """Return every joint's local rotation matrix, shape (n_frames, n_joints, 3, 3)."""
        return quat_to_matrix(self.local_quaternions())

    def local_translations_m(self) -> np.ndarray:
        """Return each joint's translation from its parent, shape (n_frames, n_joints, 3), m.

        This is the rest offset plus any position channels (usually the root's).
        """
        scale = self.skeleton.metres_per_unit
        offsets = self.skeleton.offsets * scale
        result = np.broadcast_to(offsets, (self.n_frames, len(self.skeleton), 3)).copy()
        for number, (joint, where) in enumerate(
            zip(self.skeleton.joints, self.skeleton.channel_slices(), strict=True)
        ):
            for k, channel in enumerate(joint.channels):
                if channel in POSITION_CHANNELS:
                    axis = POSITION_CHANNELS.index(channel)
                    result[:, number, axis] += self.values[:, where.start + k] * scale
        return result

    def with_values(self, values: np.ndarray, frame_time_s: float | None = None) -> "Motion":
        """Return a motion on the same skeleton with new values (and frame time)."""
        return Motion(
            self.skeleton, values, self.frame_time_s if frame_time_s is None else frame_time_s
        )
