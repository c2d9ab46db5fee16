"""Fit the upper-body model's spine, neck and head to pose landmarks, where they are seen.

The trunk's posture shows in the shoulder line and, when the hips are in the picture,
the hips → shoulders direction; the head's in the line between the ears and the ears →
nose direction. Each is spread evenly over the
joints that carry it (the three spine joints; neck and head), as the engine's spine
extension spreads its posture (seed 003 §3.2), and solved per frame by bounded least
squares (scipy.optimize.least_squares, joint limits as bounds) on those directions, so
neither the signer's size nor the camera's distance matters. The trunk's turn and the
head's turn and tilt are fitted; the rest stays at rest (see _FITTED). Parts not seen
in a frame (confidence below MIN_CONFIDENCE) keep their previous frame's posture.

Axes: files use MediaPipe's (x right, y down, z away from the camera); the engine's
world has y up and z toward the viewer, the signer facing the viewer (the signer's left
at +x).
"""

from dataclasses import dataclass

import numpy as np
from scipy.optimize import least_squares

from synthesis.rigs.body import BodyModel
from synthesis.rigs.landmarks import to_mediapipe
from synthesis.skeleton.rotations import quat_rotate

# MediaPipe pose points of the trunk and head, as fixed places on the model: a joint and
# an offset in its frame, metres (the avatar's ears, nose tip and hip joints).
BODY_POINTS = {
    "NOSE": ("head", (0.0, 0.075, 0.11)),
    "LEFT_EAR": ("head", (0.074, 0.095, 0.0)),
    "RIGHT_EAR": ("head", (-0.074, 0.095, 0.0)),
    "LEFT_HIP": ("hips", (0.09, -0.04, 0.0)),
    "RIGHT_HIP": ("hips", (-0.09, -0.04, 0.0)),
    "LEFT_SHOULDER": ("left_shoulder", (0.0, 0.0, 0.0)),
    "RIGHT_SHOULDER": ("right_shoulder", (0.0, 0.0, 0.0)),
}
MIN_CONFIDENCE = 0.5
_PARTS = {"trunk": ("spine_lower", "spine_middle", "spine_upper"), "head": ("neck", "head")}
_MOTIONS = ("flexion", "side_bend", "rotation")
STEP_RAD = 1e-4
# The shares fitted: the trunk's turn, the head's turn and tilt. Measured on rendered
# signers captured back with Holistic (spine on), the trunk's turn follows the true one
# (correlation 0.98 and 0.65 over two story sentences) but its forward and side bends
# ran against the true ones (a frontal camera's depth does not show a bend, the
# shoulder landmarks ride up with the arms, and where MediaPipe puts hips, ears and
# nose on a body biases them): those stay at rest.
_FITTED = np.array([m == "rotation" for m in _MOTIONS] + [m != "flexion" for m in _MOTIONS])


@dataclass(frozen=True)
class TrunkFit:
    """Trunk and head postures fitted to pose landmarks.

    *dofs_rad* (n_frames, n_body_dofs), the arms at rest; *found* (n_frames, 2) whether
    the trunk (shoulders) and the head (ears and nose) were seen; *miss_deg*
    (n_frames, 4) the angle between each fitted direction and the observed one
    (shoulder line, hips → shoulders, ear line, ears → nose; NaN where unseen).
    """

    dofs_rad: np.ndarray
    found: np.ndarray
    miss_deg: np.ndarray


def body_points(body: BodyModel, dofs_rad: np.ndarray) -> np.ndarray:
    """Return the BODY_POINTS (n, k, 3) of postures *dofs_rad* (n, n_dofs), world metres."""
    pose = body.pose(np.atleast_2d(dofs_rad))
    index = body.skeleton.index
    points = []
    for joint, offset in BODY_POINTS.values():
        j = index(joint)
        offset = np.asarray(offset)
        points.append(pose.positions_m[:, j] + quat_rotate(pose.quaternions[:, j], offset))
    return np.stack(points, axis=1)


def _directions(points: np.ndarray) -> np.ndarray:
    """Return the four unit directions (n, 4, 3) of BODY_POINTS-ordered points (n, k, 3)."""
    name = list(BODY_POINTS).index
    shoulders = points[:, name("LEFT_SHOULDER")] - points[:, name("RIGHT_SHOULDER")]
    middle = (points[:, name("LEFT_SHOULDER")] + points[:, name("RIGHT_SHOULDER")]) / 2
    hips = (points[:, name("LEFT_HIP")] + points[:, name("RIGHT_HIP")]) / 2
    ears = points[:, name("LEFT_EAR")] - points[:, name("RIGHT_EAR")]
    between = (points[:, name("LEFT_EAR")] + points[:, name("RIGHT_EAR")]) / 2
    nose = points[:, name("NOSE")] - between
    stacked = np.stack([shoulders, middle - hips, ears, nose], axis=1)
    return stacked / np.linalg.norm(stacked, axis=-1, keepdims=True).clip(1e-12)


def _seen(confidence: np.ndarray) -> np.ndarray:
    """Return which of the four directions (n, 4) rest on confident points."""
    ok = confidence >= MIN_CONFIDENCE
    name = list(BODY_POINTS).index
    shoulders = ok[:, name("LEFT_SHOULDER")] & ok[:, name("RIGHT_SHOULDER")]
    hips = shoulders & ok[:, name("LEFT_HIP")] & ok[:, name("RIGHT_HIP")]
    ears = ok[:, name("LEFT_EAR")] & ok[:, name("RIGHT_EAR")]
    return np.stack([shoulders, hips, ears, ears & ok[:, name("NOSE")]], axis=1)


class _Shares:
    """The six shared angles (trunk, then head: flexion, side bend, rotation) of a body."""

    def __init__(self, body: BodyModel) -> None:
        self.body = body
        names = body.dof_names
        self.columns = [
            [names.index(f"{joint}_{motion}") for joint in _PARTS[part]]
            for part in ("trunk", "head")
            for motion in _MOTIONS
        ]
        lower, upper = body.limits_rad
        # A shared angle is bounded by the tightest of the joints it is spread over.
        self.low = np.array([max(lower[c]) * len(c) for c in self.columns])
        self.high = np.array([min(upper[c]) * len(c) for c in self.columns])
        self.base = body.neutral()

    def posture(self, shares: np.ndarray) -> np.ndarray:
        """Return body DOFs (n, n_dofs) spreading *shares* (n, 6) over their joints."""
        dofs = np.repeat(self.base[None], len(shares), axis=0)
        for k, c in enumerate(self.columns):
            dofs[:, c] = shares[:, k : k + 1] / len(c)
        return dofs

    def directions(self, shares: np.ndarray) -> np.ndarray:
        """Return the four directions (n, 4, 3) of postures *shares* (n, 6)."""
        return _directions(body_points(self.body, self.posture(shares)))

    def solve(
        self, previous: np.ndarray, free: np.ndarray, used: np.ndarray, target: np.ndarray
    ) -> np.ndarray:
        """Return *previous* (6,) with its *free* shares fitted to the *used* directions."""
        low, high = self.low[free], self.high[free]

        def misses(xs: np.ndarray) -> np.ndarray:
            full = np.repeat(previous[None], len(xs), axis=0)
            full[:, free] = xs
            return (self.directions(full)[:, used] - target).reshape(len(xs), -1)

        def jacobian(x: np.ndarray) -> np.ndarray:
            # One batched pose of all perturbed postures (steps backwards at a bound).
            steps = np.where(x + STEP_RAD > high, -STEP_RAD, STEP_RAD)
            values = misses(np.vstack([x, x + np.diag(steps)]))
            return ((values[1:] - values[0]) / steps[:, None]).T

        start = np.clip(previous[free], low + 1e-9, high - 1e-9)
        solution = least_squares(
            lambda x: misses(x[None])[0],
            start,
            jac=jacobian,
            bounds=(low, high),
            xtol=1e-6,
            ftol=1e-6,
        )
        shares = previous.copy()
        shares[free] = solution.x
        return shares


def fit_trunk(body: BodyModel, points: np.ndarray, confidence: np.ndarray) -> TrunkFit:
    """Fit *body*'s spine, neck and head to pose points (n_frames, k, 3) in BODY_POINTS
    order, MediaPipe axes, any unit, with *confidence* (n_frames, k)."""
    points = to_mediapipe(points)
    observed = _directions(points)
    seen = _seen(np.asarray(confidence)) & np.isfinite(observed).all(axis=-1)
    problem = _Shares(body)
    shares = np.zeros((len(points), len(problem.columns)))
    previous = shares[0]
    for frame, used in enumerate(seen):
        # Without the ears and nose the head keeps its posture; likewise the trunk.
        free = np.array([used[0]] * 3 + [used[2]] * 3) & _FITTED
        if free.any():
            previous = problem.solve(previous, free, used, observed[frame, used])
        shares[frame] = previous
    dofs = problem.posture(shares)
    cosine = np.clip(np.sum(problem.directions(shares) * observed, axis=-1), -1.0, 1.0)
    miss = np.where(seen, np.degrees(np.arccos(cosine)), np.nan)
    found = np.stack([seen[:, 0], seen[:, 2]], axis=1)
    return TrunkFit(dofs, found, miss)
