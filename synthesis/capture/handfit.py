"""Fit the hand model's DOFs to 21 hand landmarks per frame (MediaPipe layout).

Each frame is a bounded least-squares problem (scipy.optimize.least_squares, joint
limits as bounds): the finger and thumb DOFs, and a free rotation of the whole hand
(captures see the hand from any side; the model's forearm and wrist stay at rest), so
that the model's landmarks match the observed ones. Before that, the observed hand is
centred on its palm and scaled so that the signer's wrist → middle-finger MCP length
(median over confident frames) equals the model's: a per-signer bone-length
calibration that also turns image units into metres. Residuals are weighted by
confidence; frames without the hand are interpolated from their neighbours; each frame
starts from the previous frame's answer, so a held handshape stays still.

The Jacobian comes from one batched forward-kinematics call per iteration (the model
poses all perturbed DOF vectors at once), which keeps a frame to a few milliseconds.
"""

from dataclasses import dataclass

import numpy as np
from scipy.optimize import least_squares
from scipy.spatial.transform import Rotation

from synthesis.rigs.hand import HandModel
from synthesis.rigs.landmarks import PALM_CENTRE, landmarks

WRIST, MIDDLE_MCP = 0, 9
# DOFs the fit leaves at rest: the free rotation stands for the forearm and wrist.
FIXED = ("forearm_tilt_side", "forearm_tilt_forward", "forearm_twist", "wrist_deviation",
         "wrist_flexion")  # fmt: skip
MIN_CONFIDENCE = 0.2
STEP_RAD = 1e-4


class FitError(ValueError):
    """Landmarks that cannot be fitted (no hand found, wrong shape)."""


@dataclass(frozen=True)
class HandFit:
    """A fitted hand: DOFs per frame and how well they match.

    *dofs_rad* (n_frames, n_dofs) of the model; *rotations* (n_frames, 3, 3) the hand's
    orientation in the observed frame; *scale* metres per observed unit;
    *residual_mm* (n_frames, 21) distance of each fitted landmark from the observed one
    after calibration (in the image plane when *depth* is False: the landmarks had none);
    *found* (n_frames,) whether the hand was seen (else interpolated).
    """

    dofs_rad: np.ndarray
    rotations: np.ndarray
    scale: float
    residual_mm: np.ndarray
    found: np.ndarray
    depth: bool = True

    def median_residual_mm(self) -> float:
        """Return the median landmark residual over the frames the hand was seen in."""
        seen = self.residual_mm[self.found]
        return float(np.median(seen)) if seen.size else float("nan")


def has_depth(points: np.ndarray, confidence: np.ndarray) -> bool:
    """Return whether the landmarks' z varies like a hand's depth (not flattened to a plane)."""
    seen = confidence.min(axis=1) >= MIN_CONFIDENCE
    if not seen.any():
        return True
    spread = np.ptp(points[seen], axis=1)  # (frames, 3)
    return bool(np.median(spread[:, 2]) > 0.05 * np.median(spread[:, :2].max(axis=1)))


def calibrate_scale(
    model: HandModel, points: np.ndarray, confidence: np.ndarray, planar: bool = False
) -> float:
    """Return metres per observed unit from the wrist → middle MCP length (median).

    *planar* landmarks are projections: their longest wrist → MCP length over the frames
    (the least foreshortened) stands for the true one.
    """
    rest = landmarks(model, model.neutral())
    model_length = np.linalg.norm(rest[MIDDLE_MCP] - rest[WRIST])
    seen = np.minimum(confidence[:, WRIST], confidence[:, MIDDLE_MCP]) >= MIN_CONFIDENCE
    if not seen.any():
        raise FitError("The hand was not found in any frame (no confident wrist and MCP).")
    lengths = np.linalg.norm(points[seen, MIDDLE_MCP] - points[seen, WRIST], axis=-1)
    length = float(np.percentile(lengths, 90) if planar else np.median(lengths))
    if not length > 0:
        raise FitError("The hand's wrist and middle MCP coincide: not a hand.")
    return float(model_length / length)


class _Problem:
    """One frame's least-squares problem over (rotation vector, free DOFs)."""

    def __init__(self, model: HandModel) -> None:
        self.model = model
        names = model.dof_names
        self.free = np.array([i for i, name in enumerate(names) if name not in FIXED])
        lower, upper = model.limits_rad
        self.lower = np.concatenate([np.full(3, -np.inf), lower[self.free]])
        self.upper = np.concatenate([np.full(3, np.inf), upper[self.free]])
        self.base = model.neutral()

    def dofs(self, x: np.ndarray) -> np.ndarray:
        """Return full DOF vectors (n, n_dofs) for parameter vectors (n, 3 + k)."""
        dofs = np.repeat(self.base[None], len(x), axis=0)
        dofs[:, self.free] = x[:, 3:]
        return dofs

    def predict(self, x: np.ndarray) -> np.ndarray:
        """Return the rotated model landmarks (n, 21, 3) for parameter vectors (n, 3 + k)."""
        points = landmarks(self.model, self.dofs(x))
        rotations = Rotation.from_rotvec(x[:, :3]).as_matrix()
        return np.einsum("nij,nkj->nki", rotations, points)

    def fit(self, target: np.ndarray, weights: np.ndarray, start: np.ndarray, axes: np.ndarray):
        """Return the least-squares solution for one frame's centred, scaled landmarks.

        *axes* (3,) weighs x, y and z (z 0 for landmarks without depth).
        """
        w = np.sqrt(weights)[:, None] * axes

        def residuals(x):
            return ((self.predict(x[None])[0] - target) * w).ravel()

        def jacobian(x):
            probes = np.repeat(x[None], len(x) + 1, axis=0)
            probes[1:] += np.eye(len(x)) * STEP_RAD
            # Stay inside the bounds: step backwards at an upper limit.
            over = probes[1:] > self.upper
            probes[1:][over] -= 2 * STEP_RAD
            predicted = (self.predict(probes) - target) * w
            flat = predicted.reshape(len(probes), -1)
            steps = np.where(over.any(axis=1), -STEP_RAD, STEP_RAD)
            return ((flat[1:] - flat[0]) / steps[:, None]).T

        start = np.clip(start, self.lower + 1e-9, self.upper - 1e-9)
        return least_squares(residuals, start, jac=jacobian, bounds=(self.lower, self.upper),
                             method="trf", ftol=1e-6, xtol=1e-6, max_nfev=60)  # fmt: skip


def _initial_rotation(problem: _Problem, target: np.ndarray) -> np.ndarray:
    """Return the rotation vector aligning the rest hand's palm to the observed palm (Kabsch)."""
    palm = [WRIST, 5, 9, 13, 17]
    rest = problem.predict(np.concatenate([np.zeros(3), problem.base[problem.free]])[None])[0]
    rotation, _ = Rotation.align_vectors(target[palm], rest[palm])
    return rotation.as_rotvec()


def _first_fit(problem: _Problem, target: np.ndarray, weights: np.ndarray, axes: np.ndarray):
    """Fit the first frame from several orientations; return the best solution.

    The palm alone leaves the hand's orientation ambiguous (in a projection, a hand and
    its depth-flipped twin look alike), so the palm-aligned start is tried as it is and
    turned half round each axis.
    """
    aligned = Rotation.from_rotvec(_initial_rotation(problem, target))
    best = None
    for turn in (np.zeros(3), [np.pi, 0, 0], [0, np.pi, 0], [0, 0, np.pi]):
        start = (Rotation.from_rotvec(turn) * aligned).as_rotvec()
        solution = problem.fit(target, weights, np.concatenate([start, problem.base[problem.free]]),
                               axes)  # fmt: skip
        if best is None or solution.cost < best.cost:
            best = solution
    return best


def fit_hand(
    model: HandModel, points: np.ndarray, confidence: np.ndarray | None = None,
    scale: float | None = None, depth_weight: float = 1.0,
) -> HandFit:  # fmt: skip
    """Fit *model* to landmarks *points* (n_frames, 21, 3) with *confidence* (n_frames, 21).

    *points* are in MediaPipe axes (x right, y down, z away from the camera) in any
    unit; *scale* (metres per unit) is calibrated from the hand when not given.
    *depth_weight* weighs z against x and y (a monocular estimate's depth is less sure).
    """
    points = np.asarray(points, dtype=np.float64)
    if points.ndim == 2:
        points = points[None]
    if points.ndim != 3 or points.shape[1:] != (21, 3):
        raise FitError(f"Expected hand landmarks (n_frames, 21, 3), not {points.shape}.")
    confidence = np.ones(points.shape[:2]) if confidence is None else np.asarray(confidence)
    if confidence.shape != points.shape[:2]:
        raise FitError(f"Confidences {confidence.shape} do not match landmarks {points.shape}.")
    finite = np.isfinite(points).all(axis=-1)
    confidence = np.where(finite, np.clip(np.nan_to_num(confidence), 0, 1), 0.0)
    points = np.where(finite[..., None], points, 0.0)
    axes = np.array([1.0, 1.0, depth_weight])
    if not has_depth(points, confidence):
        # Image landmarks whose depth was flattened: fit their projection only (the hand
        # is then orthographic, x and y in the image, z free).
        axes[2] = 0.0
        points = points.copy()
        points[..., 2] = 0.0
    scale = (
        calibrate_scale(model, points, confidence, planar=not axes[2])
        if scale is None
        else float(scale)
    )
    found = (confidence >= MIN_CONFIDENCE).sum(axis=1) >= 15
    problem = _Problem(model)
    n = len(points)
    solutions = np.full((n, 3 + len(problem.free)), np.nan)
    previous = None
    for frame in np.flatnonzero(found):
        weights = np.maximum(confidence[frame], 1e-3)
        palm = points[frame, list(PALM_CENTRE)].mean(axis=0)
        target = (points[frame] - palm) * scale
        if previous is None:
            solution = _first_fit(problem, target, weights, axes)
        else:
            solution = problem.fit(target, weights, previous, axes)
        solutions[frame] = previous = solution.x
    if not found.any():
        raise FitError("The hand was not found in any frame.")
    # Frames without the hand: interpolated between the fitted ones (held at the ends).
    frames = np.arange(n)
    for column in range(solutions.shape[1]):
        solutions[:, column] = np.interp(frames, frames[found], solutions[found, column])
    dofs = problem.dofs(solutions)
    rotations = Rotation.from_rotvec(solutions[:, :3]).as_matrix()
    fitted = problem.predict(solutions)
    palms = points[:, list(PALM_CENTRE)].mean(axis=1, keepdims=True)
    residual_mm = np.linalg.norm((fitted - (points - palms) * scale) * axes, axis=-1) * 1000
    return HandFit(dofs, rotations, scale, residual_mm, found, bool(axes[2]))
