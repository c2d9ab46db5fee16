"""Fit the hand model's DOFs to 21 hand landmarks per frame (MediaPipe layout).

Each frame is a bounded least-squares problem (scipy.optimize.least_squares, joint
limits as bounds): the finger and thumb DOFs, and a free rotation of the whole hand
(captures see the hand from any side; the model's forearm and wrist stay at rest), so
that the model's landmarks match the observed ones. Before that, the observed hand is
centred on its palm and scaled so that the signer's palm (median over confident
frames) is the model's size: a per-signer calibration that also turns image units into
metres. Residuals are weighted by confidence; frames without the hand are interpolated
from their neighbours. The stillest frame is fitted from several starts; from it each
frame starts from its neighbour's answer, forwards and backwards, so a held handshape
stays still.

The Jacobian comes from one batched forward-kinematics call per iteration (the model
poses all perturbed DOF vectors at once), which keeps a frame to a few milliseconds.
"""

from dataclasses import dataclass

import numpy as np
from scipy.optimize import least_squares
from scipy.spatial.transform import Rotation

from synthesis.rigs.hand import FINGERS, HandModel
from synthesis.rigs.landmarks import LANDMARK_JOINTS, PALM_CENTRE, landmarks

WRIST, MIDDLE_MCP = 0, 9
# The palm: the wrist and the four finger MCPs, nearly coplanar.
PALM_POINTS = (0, 5, 9, 13, 17)
# DOFs the fit leaves at rest: the free rotation stands for the forearm and wrist.
FIXED = (
    "forearm_tilt_side",
    "forearm_tilt_forward",
    "forearm_twist",
    "wrist_deviation",
    "wrist_flexion",
)
MIN_CONFIDENCE = 0.2
STEP_RAD = 1e-4
# The finger flexion of the curled start, degrees (a loose fist).
CURLED_DEG = 70.0
# Each landmark's parent in the hand's tree (MediaPipe's connections from the wrist).
LANDMARK_PARENTS = (-1, 0, 1, 2, 3, 0, 5, 6, 7, 0, 9, 10, 11, 0, 13, 14, 15, 0, 17, 18, 19)
# How far a signer's bone may differ from the model's, as a ratio of lengths.
BONE_RATIO_LIMITS = (0.7, 1.4)
# Flexion of a finger's distal joint follows its middle joint: DIP ≈ 2/3 PIP (the
# tendon coupling of Rijpkema & Girard 1991); a soft prior, weighed by *coupling*.
DIP_PIP_RATIO = 2 / 3
# Weight of that prior: a 20° departure costs what a ~2 mm landmark miss does. Measured
# on rendered clips captured back (bench/bench_capture.py), it halves the 95th
# percentile of the finger error and brings its median under 8°.
COUPLING = 0.03
# The smoothing window (7 frames at 30 fps): short enough to keep a 200 ms hold, long
# enough to damp frame-to-frame tracking noise.
SMOOTH_S = 0.24


class FitError(ValueError):
    """Landmarks that cannot be fitted (no hand found, wrong shape)."""


@dataclass(frozen=True)
class HandFit:
    """A fitted hand: DOFs per frame and how well they match.

    *dofs_rad* (n_frames, n_dofs) of the model; *rotations* (n_frames, 3, 3) the hand's
    orientation in the observed frame; *scale* metres per observed unit;
    *residual_mm* (n_frames, 21) distance of each fitted landmark from the observed one
    after calibration (in the image plane when *depth* is False: the landmarks had none);
    *found* (n_frames,) whether the hand was seen (else interpolated); *bone_scale*
    (n_joints,) the signer's bone lengths over the model's, when calibrated.
    """

    dofs_rad: np.ndarray
    rotations: np.ndarray
    scale: float
    residual_mm: np.ndarray
    found: np.ndarray
    depth: bool = True
    bone_scale: np.ndarray | None = None

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
    """Return metres per observed unit from the palm's size (median over the frames).

    With depth, the size is the wrist → middle MCP length. *planar* landmarks are
    projections, which foreshorten the palm along its tilt: the palm (wrist and four
    MCPs, nearly flat) maps to its projection by a 2-D linear map whose larger singular
    value is the scale whatever the tilt, so that value stands for the palm's size.
    """
    rest = landmarks(model, model.neutral())
    palm = list(PALM_POINTS)
    seen = (confidence[:, palm] >= MIN_CONFIDENCE).all(axis=1)
    if not seen.any():
        raise FitError("The hand was not found in any frame (no confident wrist and MCPs).")
    if planar:
        # The model palm in its own plane (the rest hand's x and y: its palm faces z).
        model_palm = rest[palm, :2] - rest[palm, :2].mean(axis=0)
        observed = points[seen][:, palm, :2]
        observed = observed - observed.mean(axis=1, keepdims=True)
        maps = np.linalg.pinv(model_palm) @ observed  # (frames, 2, 2): model → image
        sizes = np.linalg.svd(maps, compute_uv=False)[:, 0]  # image units per metre
        size = float(np.median(sizes))
        if not size > 0:
            raise FitError("The hand's palm landmarks coincide: not a hand.")
        return 1.0 / size
    model_length = np.linalg.norm(rest[MIDDLE_MCP] - rest[WRIST])
    lengths = np.linalg.norm(points[seen, MIDDLE_MCP] - points[seen, WRIST], axis=-1)
    length = float(np.median(lengths))
    if not length > 0:
        raise FitError("The hand's wrist and middle MCP coincide: not a hand.")
    return float(model_length / length)


def calibrate_bones(
    model: HandModel, points: np.ndarray, confidence: np.ndarray, scale: float
) -> np.ndarray:
    """Return each skeleton joint's offset scale (n_joints,) giving the signer's proportions.

    Each landmark segment's length (median over the frames both ends are confidently
    seen, times *scale*) over the model's gives the ratio for the bones between them,
    within :data:`BONE_RATIO_LIMITS`. Needs landmarks with depth: a projection
    foreshortens segments.
    """
    skeleton = model.skeleton
    parents = skeleton.parents
    rest = landmarks(model, model.neutral())
    bone_scale = np.ones(len(skeleton))
    for k, p in enumerate(LANDMARK_PARENTS):
        if p < 0:
            continue
        seen = np.minimum(confidence[:, k], confidence[:, p]) >= MIN_CONFIDENCE
        if seen.sum() < 1:
            continue
        observed = np.median(np.linalg.norm(points[seen, k] - points[seen, p], axis=-1)) * scale
        expected = np.linalg.norm(rest[k] - rest[p])
        if not expected > 0:
            continue
        ratio = float(np.clip(observed / expected, *BONE_RATIO_LIMITS))
        joint, top = skeleton.index(LANDMARK_JOINTS[k]), skeleton.index(LANDMARK_JOINTS[p])
        while joint >= 0 and joint != top:
            bone_scale[joint] = ratio
            joint = parents[joint]
    return bone_scale


class _Problem:
    """One frame's least-squares problem over (rotation vector, free DOFs)."""

    def __init__(
        self, model: HandModel, bone_scale: np.ndarray | None = None, coupling: float = 0.0
    ) -> None:
        self.model = model
        self.bone_scale = bone_scale
        names = model.dof_names
        self.free = np.array([i for i, name in enumerate(names) if name not in FIXED])
        lower, upper = model.limits_rad
        self.lower = np.concatenate([np.full(3, -np.inf), lower[self.free]])
        self.upper = np.concatenate([np.full(3, np.inf), upper[self.free]])
        self.base = model.neutral()
        # A start with the fingers curled (their flexions at CURLED_DEG, within limits).
        curled = self.base.copy()
        for i in self.free:
            if names[i].split("_")[0] in FINGERS and names[i].endswith("_flexion"):
                curled[i] = np.clip(np.radians(CURLED_DEG), lower[i], upper[i])
        self.curled = curled[self.free]
        # The DIP–PIP coupling prior: rows of (dip − ratio·pip), weighted, in x's columns.
        column = {names[i]: 3 + k for k, i in enumerate(self.free)}
        rows = []
        for finger in ("index", "middle", "ring", "pinky"):
            dip, pip = column.get(f"{finger}_dip_flexion"), column.get(f"{finger}_pip_flexion")
            if dip is not None and pip is not None:
                row = np.zeros(3 + len(self.free))
                row[dip], row[pip] = 1.0, -DIP_PIP_RATIO
                rows.append(row)
        self.prior = coupling * np.array(rows).reshape(-1, 3 + len(self.free))

    def dofs(self, x: np.ndarray) -> np.ndarray:
        """Return full DOF vectors (n, n_dofs) for parameter vectors (n, 3 + k)."""
        dofs = np.repeat(self.base[None], len(x), axis=0)
        dofs[:, self.free] = x[:, 3:]
        return dofs

    def predict(self, x: np.ndarray) -> np.ndarray:
        """Return the rotated model landmarks (n, 21, 3) for parameter vectors (n, 3 + k)."""
        points = landmarks(self.model, self.dofs(x), self.bone_scale)
        rotations = Rotation.from_rotvec(x[:, :3]).as_matrix()
        return np.einsum("nij,nkj->nki", rotations, points)

    def fit(self, target: np.ndarray, weights: np.ndarray, start: np.ndarray, axes: np.ndarray):
        """Return the least-squares solution for one frame's centred, scaled landmarks.

        *axes* (3,) weighs x, y and z (z 0 for landmarks without depth).
        """
        w = np.sqrt(weights)[:, None] * axes

        def residuals(x):
            return np.concatenate(
                [((self.predict(x[None])[0] - target) * w).ravel(), self.prior @ x]
            )

        def jacobian(x):
            probes = np.repeat(x[None], len(x) + 1, axis=0)
            probes[1:] += np.eye(len(x)) * STEP_RAD
            # Stay inside the bounds: step backwards at an upper limit.
            over = probes[1:] > self.upper
            probes[1:][over] -= 2 * STEP_RAD
            predicted = (self.predict(probes) - target) * w
            flat = predicted.reshape(len(probes), -1)
            steps = np.where(over.any(axis=1), -STEP_RAD, STEP_RAD)
            return np.vstack([((flat[1:] - flat[0]) / steps[:, None]).T, self.prior])

        start = np.clip(start, self.lower + 1e-9, self.upper - 1e-9)
        return least_squares(
            residuals,
            start,
            jac=jacobian,
            bounds=(self.lower, self.upper),
            method="trf",
            ftol=1e-6,
            xtol=1e-6,
            max_nfev=60,
        )


def _initial_rotation(problem: _Problem, target: np.ndarray) -> np.ndarray:
    """Return the rotation vector aligning the rest hand's palm to the observed palm (Kabsch)."""
    palm = list(PALM_POINTS)
    rest = problem.predict(np.concatenate([np.zeros(3), problem.base[problem.free]])[None])[0]
    rotation, _ = Rotation.align_vectors(target[palm], rest[palm])
    return rotation.as_rotvec()


def _stillest(points: np.ndarray, seen: np.ndarray) -> int:
    """Return the seen frame whose landmarks move least (from the previous seen frame)."""
    if len(seen) < 3:
        return int(seen[0])
    palm = points[seen][:, list(PALM_CENTRE)].mean(axis=1, keepdims=True)
    shape = points[seen] - palm
    motion = np.linalg.norm(np.diff(shape, axis=0), axis=-1).mean(axis=1)
    # A frame's stillness: its motion to both neighbours (the two ends are not chosen).
    both = np.concatenate([[np.inf], motion]) + np.concatenate([motion, [np.inf]])
    return int(seen[np.argmin(both)])


def _first_fit(problem: _Problem, target: np.ndarray, weights: np.ndarray, axes: np.ndarray):
    """Fit a frame afresh from several starts; return the best solution.

    The palm alone leaves the hand's orientation ambiguous (in a projection, a hand and
    its depth-flipped twin look alike), so the palm-aligned start is tried as it is and
    turned half round each axis; and curled fingers seen end-on are reached from a
    curled start, not from open ones, so each turn starts open and curled.
    """
    aligned = Rotation.from_rotvec(_initial_rotation(problem, target))
    best = None
    for fingers in (problem.base[problem.free], problem.curled):
        for turn in (np.zeros(3), [np.pi, 0, 0], [0, np.pi, 0], [0, 0, np.pi]):
            start = (Rotation.from_rotvec(turn) * aligned).as_rotvec()
            solution = problem.fit(target, weights, np.concatenate([start, fingers]), axes)
            if best is None or solution.cost < best.cost:
                best = solution
    return best


def _smooth(values: np.ndarray, rate_hz: float, smooth_s: float, problem: _Problem):
    """Return DOF curves (n_frames, k) smoothed by a quadratic Savitzky–Golay filter."""
    from scipy.signal import savgol_filter

    window = round(smooth_s * rate_hz) | 1  # odd
    if window < 5 or len(values) < window:
        return values
    smoothed = savgol_filter(values, window, 2, axis=0, mode="interp")
    return np.clip(smoothed, problem.lower[3:], problem.upper[3:])


def _checked_landmarks(points, confidence) -> tuple[np.ndarray, np.ndarray]:
    """Return landmarks (n_frames, 21, 3) and confidences, a missing point at confidence 0;
    FitError names a shape that is not a hand's."""
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
    return points, confidence


def _track(problem, solutions, targets, weights, axes, found, points) -> None:
    """Fill *solutions* at the frames where the hand was *found*."""
    # Fit the stillest frame afresh, then track from it forwards and backwards: a
    # recording's first frames are often a transition, whose shape, carried into the
    # hold by tracking, can hold the fit in a wrong answer.
    seen = np.flatnonzero(found)
    anchor = _stillest(points, seen)
    solutions[anchor] = _first_fit(problem, targets[anchor], weights[anchor], axes).x
    for run in (seen[seen > anchor], seen[seen < anchor][::-1]):
        previous = solutions[anchor]
        for frame in run:
            previous = problem.fit(targets[frame], weights[frame], previous, axes).x
            solutions[frame] = previous


def fit_hand(
    model: HandModel,
    points: np.ndarray,
    confidence: np.ndarray | None = None,
    scale: float | None = None,
    depth_weight: float = 1.0,
    bones: bool = False,
    coupling: float = COUPLING,
    rate_hz: float | None = None,
    smooth_s: float = SMOOTH_S,
) -> HandFit:
    """Fit *model* to landmarks *points* (n_frames, 21, 3) with *confidence* (n_frames, 21).

    *points* are in MediaPipe axes (x right, y down, z away from the camera) in any
    unit; *scale* (metres per unit) is calibrated from the hand when not given.
    *depth_weight* weighs z against x and y (a monocular estimate's depth is less sure).
    *bones* calibrates each bone's length to the signer's (:func:`calibrate_bones`;
    only for landmarks with depth; off by default: on rendered clips it made the joint
    angles worse). *coupling* weighs the DIP–PIP prior (0 for none). With *rate_hz*
    (frames per second) the DOF curves are smoothed over *smooth_s* seconds by a
    Savitzky–Golay filter, which keeps holds flat and follows transitions.
    """
    points, confidence = _checked_landmarks(points, confidence)
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
    if not found.any():
        raise FitError("The hand was not found in any frame.")
    bone_scale = calibrate_bones(model, points, confidence, scale) if bones and axes[2] else None
    problem = _Problem(model, bone_scale, coupling)
    n = len(points)
    solutions = np.full((n, 3 + len(problem.free)), np.nan)
    targets = (points - points[:, list(PALM_CENTRE)].mean(axis=1, keepdims=True)) * scale
    weights = np.maximum(confidence, 1e-3)
    _track(problem, solutions, targets, weights, axes, found, points)
    # Frames without the hand: interpolated between the fitted ones (held at the ends).
    frames = np.arange(n)
    for column in range(solutions.shape[1]):
        solutions[:, column] = np.interp(frames, frames[found], solutions[found, column])
    if rate_hz is not None:
        solutions[:, 3:] = _smooth(solutions[:, 3:], rate_hz, smooth_s, problem)
    dofs = problem.dofs(solutions)
    rotations = Rotation.from_rotvec(solutions[:, :3]).as_matrix()
    fitted = problem.predict(solutions)
    residual_mm = np.linalg.norm((fitted - targets) * axes, axis=-1) * 1000
    return HandFit(dofs, rotations, scale, residual_mm, found, bool(axes[2]), bone_scale)
