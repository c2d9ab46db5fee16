"""Transition times from pose distance: ``t = a + b · d(from, to)`` (seed 000 §4.2.2).

The distance between two letters' poses is RMSD (seed 000's choice: r = 0.44),
Manhattan (r = 0.42) or Chebyshev (r = 0.38) over one difference per component, in
radians, or the GPLVM distance (r = 0.22; :mod:`synthesis.timing.gplvm`, 0 to 1, over
the letters' whole poses whatever the space). Two spaces of components (``SPACES``):

- ``"joints"`` (the default, the paper's): one value per joint, a = (a₁ … aₙ) "with
  n = 18 joints" in seed 000's hand model; here the hand model's 17 articulated joints
  (forearm, wrist and 15 digit joints), each joint's difference the angle of the
  rotation between its two local rotations, so that a joint that bends about two axes
  counts once, by how far it turns;
- ``"dofs"``: one value per DOF of the hand model (30, five of them forearm and wrist
  placement), as the engine measured before; models saved without a space used it.

All are symmetric, so A→B and B→A take the same time. Over joints, the letters range
from 0 to 1.37 rad and E–Z is 0.63 rad (seed 000: 0 to 1.10, E–Z 0.51; the same share
of the range, 46 %).
"""

from dataclasses import dataclass
from functools import cache

import numpy as np
from scipy import stats

from synthesis.fingerspelling.alphabet import letter_pose
from synthesis.skeleton.rotations import quat_multiply

METRICS = ("rmsd", "manhattan", "chebyshev", "gplvm")
# Seed 000 Fig. 4.7: each metric's correlation with the recorded transition times.
PUBLISHED_TRANSITION_R = {"rmsd": 0.44, "manhattan": 0.42, "chebyshev": 0.38, "gplvm": 0.22}
# Seed 000 §4.2.2: the chosen RMSD line's mean error.
PUBLISHED_RMSD_ERROR_MS = 44.69
PUBLISHED_TRANSITIONS_INPUT = "recorded transitions (seed 000 §4.2.2, Fig. 4.7)"
SPACES = ("joints", "dofs")
DEFAULT_SPACE = "joints"


def pose_distance(a_rad: np.ndarray, b_rad: np.ndarray, metric: str = "rmsd") -> np.ndarray:
    """Return the distance between DOF vectors (..., n_dofs), radians."""
    difference = np.asarray(a_rad) - np.asarray(b_rad)
    if metric == "gplvm":
        raise ValueError("The GPLVM distance is between letters (letter_distance), not vectors.")
    if metric == "rmsd":
        return np.sqrt(np.mean(difference**2, axis=-1))
    if metric == "manhattan":
        return np.sum(np.abs(difference), axis=-1)
    if metric == "chebyshev":
        return np.max(np.abs(difference), axis=-1)
    raise ValueError(f"Unknown distance {metric!r}; use one of {', '.join(METRICS)}.")


@cache
def _hand():
    from synthesis.rigs.hand import HandModel

    hand = HandModel("right")
    moved = {dof.joint for dof in hand.dofs}
    joints = [i for i, joint in enumerate(hand.skeleton.joints) if joint.name in moved]
    return hand, np.array(joints)


def _joint_rotations(dofs_rad: np.ndarray) -> np.ndarray:
    hand, joints = _hand()
    return hand.local_quaternions(np.asarray(dofs_rad, dtype=float))[..., joints, :]


@cache
def _letter_rotations(letter: str) -> np.ndarray:
    return _joint_rotations(letter_pose(letter))


def joint_differences(a_rad: np.ndarray, b_rad: np.ndarray) -> np.ndarray:
    """Return, per articulated joint of the hand model, the angle (rad) between the joint's
    local rotations in two DOF vectors (..., 30) → (..., 17)."""
    return _rotation_angles(_joint_rotations(a_rad), _joint_rotations(b_rad))


def _rotation_angles(qa: np.ndarray, qb: np.ndarray) -> np.ndarray:
    relative = quat_multiply(qa * np.array([-1.0, -1.0, -1.0, 1.0]), qb)  # (x, y, z, w)
    # atan2 of the halves stays exact near zero, where arccos of a dot product does not.
    return 2.0 * np.arctan2(np.linalg.norm(relative[..., :3], axis=-1), np.abs(relative[..., 3]))


def letter_distance(
    first: str, second: str, metric: str = "rmsd", space: str = DEFAULT_SPACE
) -> float:
    """Return the distance between two letters' poses (radians) over joints or DOFs.

    Right-hand poses (a mirror image changes no distance); J and Z by their base poses.
    """
    if space not in SPACES:
        raise ValueError(f"Unknown distance space {space!r}; use one of {', '.join(SPACES)}.")
    if metric == "gplvm":
        from synthesis.timing.gplvm import gplvm_distance

        return gplvm_distance(first, second)
    if space == "dofs":
        return float(pose_distance(letter_pose(first), letter_pose(second), metric))
    angles = _rotation_angles(_letter_rotations(first), _letter_rotations(second))
    return float(pose_distance(angles, 0.0, metric))


@dataclass(frozen=True)
class TransitionModel:
    """A fitted line: intercept (ms), slope (ms per radian), its metric, the space the
    distance is measured in (``SPACES``) and fit statistics."""

    intercept_ms: float
    slope_ms_per_rad: float
    metric: str = "rmsd"
    r: float = float("nan")
    mean_abs_error_ms: float = float("nan")
    nobs: int = 0
    minimum_ms: float = 1000.0 / 120.0
    space: str = DEFAULT_SPACE

    @classmethod
    def fit(
        cls,
        distances_rad: np.ndarray,
        times_ms: np.ndarray,
        metric: str = "rmsd",
        space: str = DEFAULT_SPACE,
    ) -> "TransitionModel":
        """Fit by least squares (scipy.stats.linregress) to measured transitions."""
        distances = np.asarray(distances_rad, dtype=float)
        times = np.asarray(times_ms, dtype=float)
        if distances.shape != times.shape or distances.size < 3:
            raise ValueError("Fitting transitions needs at least 3 (distance, time) pairs.")
        fit = stats.linregress(distances, times)
        predicted = fit.intercept + fit.slope * distances
        return cls(
            float(fit.intercept),
            float(fit.slope),
            metric,
            float(fit.rvalue),
            float(np.abs(predicted - times).mean()),
            int(distances.size),
            space=space,
        )

    def predict_ms(self, first: str, second: str) -> float:
        """Return the transition time (ms) from one letter to the next, at least one frame."""
        distance = letter_distance(first, second, self.metric, self.space)
        return max(self.intercept_ms + self.slope_ms_per_rad * distance, self.minimum_ms)

    def to_dict(self) -> dict:
        return {
            "intercept_ms": self.intercept_ms,
            "slope_ms_per_rad": self.slope_ms_per_rad,
            "metric": self.metric,
            "r": self.r,
            "mean_abs_error_ms": self.mean_abs_error_ms,
            "nobs": self.nobs,
            "minimum_ms": self.minimum_ms,
            "space": self.space,
        }

    @classmethod
    def from_dict(cls, data: dict) -> "TransitionModel":
        """Return the model saved by ``to_dict``; one saved without a space measured DOFs."""
        if data.get("metric", "rmsd") not in METRICS:
            raise ValueError(f"Unknown distance {data.get('metric')!r} in a transition model.")
        if data.get("space", "dofs") not in SPACES:
            raise ValueError(f"Unknown distance space {data.get('space')!r} in a transition model.")
        fields = {k: data[k] for k in data if k in cls.__dataclass_fields__}
        return cls(**{"space": "dofs", **fields})
