"""Measure how fast each joint turns: the angle between a joint's local rotation in two
frames, times the frame rate.

A joint's local rotation is its global one seen from its parent (q_parent⁻¹ q_joint), so
a hand carried by a turning trunk does not count the trunk's turn again. Measured on
joint transforms, the same figure comes from DOF vectors, a captured Pose or an imported
motion. The reference a clip is judged against is the same item keyed (its signs' own
keyframes, nothing synthesised between them): issue 53's Hermite join flung the wrist at
7.1 × the keyed peak while every other technique stayed within 1.1–1.7 ×.
"""

from dataclasses import dataclass

import numpy as np

from synthesis.skeleton.kinematics import Pose
from synthesis.skeleton.rotations import quat_conjugate, quat_multiply

# Below this a joint's keyed peak is a joint at rest: a technique that adds a little
# motion to it (liveliness, a spine that turns) is not a fling. 120 °/s is about a
# quarter of the slowest keyed arm peak among the story sentences (seed 003).
RESTING_PEAK_DEG_S = 120.0


def local_quaternions(pose: Pose, parents: np.ndarray) -> np.ndarray:
    """Return each joint's rotation relative to its parent, (n_frames, n_joints, 4).

    Roots keep their global rotation.
    """
    q = np.asarray(pose.quaternions, dtype=np.float64)
    parents = np.asarray(parents)
    parent_q = np.where(
        (parents >= 0)[None, :, None], q[:, np.maximum(parents, 0)], np.array([0.0, 0.0, 0.0, 1.0])
    )
    return quat_multiply(quat_conjugate(parent_q), q)


def joint_speeds_deg_s(pose: Pose, parents: np.ndarray, rate_hz: float) -> np.ndarray:
    """Return each joint's angular speed between consecutive frames, (n_frames − 1, n_joints)."""
    local = local_quaternions(pose, parents)
    if len(local) < 2:
        return np.zeros((0, local.shape[1]))
    dot = np.abs(np.sum(local[1:] * local[:-1], axis=-1))
    return np.degrees(2.0 * np.arccos(np.clip(dot, 0.0, 1.0))) * rate_hz


@dataclass(frozen=True)
class SpeedCheck:
    """Per joint, the clip's peak angular speed and its keyed reference's, in °/s, and the
    frame of the clip's peak; *names* the joints."""

    names: tuple[str, ...]
    peak_deg_s: np.ndarray
    reference_deg_s: np.ndarray
    peak_frame: np.ndarray

    def ratios(self) -> np.ndarray:
        """Return each joint's peak over its reference's (a resting joint's reference is
        :data:`RESTING_PEAK_DEG_S`)."""
        return self.peak_deg_s / np.maximum(self.reference_deg_s, RESTING_PEAK_DEG_S)

    def too_fast(self, factor: float) -> list[int]:
        """Return the joints (indices) whose peak exceeds *factor* × their reference's,
        fastest first."""
        ratios = self.ratios()
        over = np.flatnonzero(ratios > factor)
        return [int(j) for j in over[np.argsort(-ratios[over])]]


def compare_speeds(
    pose: Pose, reference: Pose, parents: np.ndarray, names, rate_hz: float
) -> SpeedCheck:
    """Return the peak joint speeds of *pose* against those of *reference* (same skeleton)."""
    speeds = joint_speeds_deg_s(pose, parents, rate_hz)
    keyed = joint_speeds_deg_s(reference, parents, rate_hz)
    n_joints = len(parents)
    peak = speeds.max(axis=0) if len(speeds) else np.zeros(n_joints)
    frame = speeds.argmax(axis=0) + 1 if len(speeds) else np.zeros(n_joints, dtype=int)
    reference_peak = keyed.max(axis=0) if len(keyed) else np.zeros(n_joints)
    return SpeedCheck(tuple(names), peak, reference_peak, frame)
