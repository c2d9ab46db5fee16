"""Fit the upper-body model's arms to pose landmarks, and export body motions as them.

MediaPipe Pose (and Holistic) gives each shoulder, elbow and wrist; the hands give 21
landmarks each. Per frame and arm, the observed arm is scaled to the model's arm
length (a per-signer calibration: the median over the frames of shoulder → elbow →
wrist), its wrist becomes the target of the analytic arm IK
(:func:`synthesis.rigs.ik.solve_arm`), the elbow's place on its circle gives the
swivel, and the hand's landmarks give the wrist's orientation (palm normal and finger
direction), hence forearm twist and wrist; the fingers are fitted by
:func:`synthesis.capture.handfit.fit_hand`. Before the arms, the spine, neck and head
are fitted where the shoulders, hips, ears and nose are seen
(:func:`synthesis.capture.trunkfit.fit_trunk`); the arms hang from the shoulders it
places.

Axes: files use MediaPipe's (x right, y down, z away from the camera); the engine's
world has y up and z toward the viewer.
"""

from dataclasses import dataclass

import numpy as np

from synthesis.capture.depth import ARM_POINTS, MIN_CONFIDENCE, depth_from_lengths, flat_depth
from synthesis.capture.posefile import (
    EXPORT_METRES_PER_UNIT,
    EXPORT_SIZE,
    HAND_COMPONENTS,
    POSE_COMPONENT,
    POSE_WORLD_COMPONENT,
    PoseFileError,
    PoseRecording,
)
from synthesis.capture.trunkfit import BODY_POINTS, TrunkFit, body_points, fit_trunk
from synthesis.rigs.body import BodyModel
from synthesis.rigs.landmarks import LANDMARK_JOINTS, LANDMARK_NAMES, to_mediapipe

POSE_POINTS = (*ARM_POINTS["left"], *ARM_POINTS["right"])
_names = list(BODY_POINTS)
# The trunk's and head's points that are not also an arm's (BODY_POINTS positions).
_HEAD_AND_HIPS = tuple(k for k, name in enumerate(_names) if name not in POSE_POINTS)
# Hand landmarks (MediaPipe order) that frame the palm: wrist, index and pinky MCPs.
_WRIST, _INDEX_MCP, _MIDDLE_MCP, _PINKY_MCP = 0, 5, 9, 17


@dataclass(frozen=True)
class ArmFit:
    """Body DOFs fitted to pose landmarks and how far the fitted joints are from them.

    *dofs_rad* (n_frames, n_body_dofs); *residual_mm* (n_frames, 6) the fitted shoulder,
    elbow and wrist of the left then right arm against the observed ones, both scaled
    to the model and placed at the model's shoulders; *found* (n_frames, 2) whether
    each arm (left, right) was seen; *trunk* the spine, neck and head fit (None when
    the recording has no head or hips: the trunk then stays at rest). *depth* says
    where the points' depth came from: "file", or "lengths" where the file's was flat
    (:mod:`synthesis.capture.depth`); *image_miss* (n_frames, 6) how far the fitted
    shoulders, elbows and wrists fall from the file's image landmarks, seen from the
    camera, in shoulder widths (NaN where unseen; None without image landmarks).
    """

    dofs_rad: np.ndarray
    residual_mm: np.ndarray
    found: np.ndarray
    trunk: TrunkFit | None = None
    depth: str = "file"
    image_miss: np.ndarray | None = None


def _joint(body: BodyModel, side: str, part: str) -> int:
    return body.skeleton.index(f"{side}_{part.lower()}")


BODY_COMPONENTS = (
    (POSE_COMPONENT, (*POSE_POINTS, *(_names[k] for k in _HEAD_AND_HIPS))),
    (HAND_COMPONENTS["left"], LANDMARK_NAMES),
    (HAND_COMPONENTS["right"], LANDMARK_NAMES),
)


def body_landmarks_m(body: BodyModel, dofs_rad: np.ndarray) -> np.ndarray:
    """Return the :data:`BODY_COMPONENTS` points (n_frames, k, 3) of body DOFs
    (n_frames, n_dofs), engine axes, metres: shoulders, elbows, wrists, nose, ears and
    hips, then both hands' 21 landmarks."""
    positions = body.pose(np.atleast_2d(dofs_rad)).positions_m
    index = body.skeleton.index
    arms = positions[:, [index(name.lower()) for name in POSE_POINTS]]
    pose = np.concatenate([arms, body_points(body, dofs_rad)[:, list(_HEAD_AND_HIPS)]], axis=1)
    hands = [
        positions[:, [index(f"{side}_{joint}") for joint in LANDMARK_JOINTS]]
        for side in ("left", "right")
    ]
    return np.concatenate([pose, *hands], axis=1)


def from_body_motion(body: BodyModel, dofs_rad: np.ndarray, rate_hz: float) -> PoseRecording:
    """Return body DOFs (n_frames, n_dofs) as a .pose recording of
    :func:`body_landmarks_m`, in millimetres.

    The shoulders' midpoint sits at the middle of a 1000 × 1000 "image" (a clip's
    export is in its frame's pixels instead: :mod:`synthesis.capture.filmed`).
    """
    points = to_mediapipe(body_landmarks_m(body, dofs_rad))
    centre = points[:, : len(POSE_POINTS)][:, [0, 3]].mean(axis=1, keepdims=True)
    units = (points - centre) / EXPORT_METRES_PER_UNIT + np.array([EXPORT_SIZE / 2] * 2 + [0.0])
    components = BODY_COMPONENTS
    return PoseRecording(
        float(rate_hz),
        components,
        units,
        np.ones(units.shape[:2]),
        EXPORT_SIZE,
        EXPORT_SIZE,
        EXPORT_METRES_PER_UNIT,
    )


def _palm_frame(hand: np.ndarray) -> np.ndarray:
    """Return the palm's frames (n, 3, 3) from hand landmarks (n, 21, 3), engine axes:
    y along the fingers (wrist → middle MCP), z across the palm's normal."""
    from synthesis.rigs.ik import hand_frame

    fingers = hand[:, _MIDDLE_MCP] - hand[:, _WRIST]
    across = hand[:, _INDEX_MCP] - hand[:, _PINKY_MCP]
    return np.stack(
        [hand_frame(p, f) for p, f in zip(np.cross(fingers, across), fingers, strict=True)]
    )


def _wrist_in_palm(body: BodyModel, side: str) -> np.ndarray:
    """Return the wrist joint's frame in the palm frame (3, 3), read off the model at rest."""
    from synthesis.skeleton.rotations import quat_to_matrix

    pose = body.pose(body.neutral())
    marks = pose.positions_m[:, [body.skeleton.index(f"{side}_{j}") for j in LANDMARK_JOINTS]]
    wrist = quat_to_matrix(pose.quaternions[0, body.skeleton.index(f"{side}_wrist")])
    return _palm_frame(marks)[0].T @ wrist


def _arm_targets(body, side: str, rest, shoulder, arm_points, seen):
    """Return the elbow and wrist targets (n, 3): the landmarks' arm directions from the
    fitted shoulder, scaled to the model's arm length."""
    model_arm = np.linalg.norm(
        rest[_joint(body, side, "elbow")] - rest[_joint(body, side, "shoulder")]
    ) + np.linalg.norm(rest[_joint(body, side, "wrist")] - rest[_joint(body, side, "elbow")])
    upper = arm_points[:, 1] - arm_points[:, 0]
    lower = arm_points[:, 2] - arm_points[:, 1]
    observed_arm = np.median(
        np.linalg.norm(upper[seen], axis=1) + np.linalg.norm(lower[seen], axis=1)
    )
    scale = model_arm / observed_arm
    elbow_t = shoulder + upper * scale
    return elbow_t, elbow_t + lower * scale


def _fit_hand_of(body, recording: PoseRecording, side: str, dofs):
    """Return the wrist's world frames from the hand landmarks (None without a seen hand)
    and *dofs* with the hand's fingers fitted where the fit finds them."""
    from synthesis.capture.handfit import FitError, fit_hand
    from synthesis.rigs.hand import HandModel

    marks, marks_confidence = recording.hand(side)
    hand_seen = marks_confidence.min(axis=1) >= MIN_CONFIDENCE
    if not hand_seen.any():
        return None, dofs
    rotation = _palm_frame(to_mediapipe(marks)) @ _wrist_in_palm(body, side)
    # Frames without the hand keep the nearest seen hand's orientation.
    rotation = rotation[_nearest_seen(hand_seen)]
    try:
        fit = fit_hand(HandModel(side), marks, marks_confidence, rate_hz=recording.fps)
        dofs = body.with_hand(dofs, side, fit.dofs_rad)
    except FitError:  # no confident frame: the fingers keep their rest pose
        pass
    return rotation, dofs


def fit_arms(
    body: BodyModel, recording: PoseRecording, sides=("right", "left"), hands: bool = True
) -> ArmFit:
    """Fit *body*'s arms (and with *hands*, fingers and wrists) to *recording*'s landmarks.

    Raise PoseFileError if the recording has no pose landmarks or no arm in any frame.
    """
    from synthesis.rigs.ik import solve_arm

    # Holistic's metric pose, where the file has it: its depth is far surer than the
    # image landmarks' (the arm fit only needs directions and proportions). A file may
    # have flattened both: the depth is then rebuilt from the model's proportions.
    world = recording.found_component(POSE_WORLD_COMPONENT)
    component = POSE_COMPONENT
    if world and not flat_depth(recording, POSE_WORLD_COMPONENT):
        component = POSE_WORLD_COMPONENT
    image = recording
    depth = "file"
    if recording.has_component(component) and flat_depth(recording, component):
        recording, depth = depth_from_lengths(recording, component, body), "lengths"
    points, confidence = recording.component(component, POSE_POINTS)
    points = to_mediapipe(points)
    n = recording.n_frames
    trunk = _fit_trunk(body, recording, component)
    dofs = np.zeros((n, len(body.dofs))) if trunk is None else trunk.dofs_rad.copy()
    rest = body.pose(body.neutral()).positions_m[0]
    # The shoulders where the fitted trunk puts them.
    posed = body.pose(dofs).positions_m
    found = np.zeros((n, 2), dtype=bool)
    residual = np.full((n, 6), np.nan)
    fitted_any = False
    for column, side in enumerate(("left", "right")):
        if side not in sides:
            continue
        s, e, w = (3 * column + k for k in range(3))
        seen = confidence[:, [s, e, w]].min(axis=1) >= MIN_CONFIDENCE
        found[:, column] = seen
        if not seen.any():
            continue
        fitted_any = True
        shoulder = posed[:, _joint(body, side, "shoulder")]
        elbow_t, wrist_t = _arm_targets(body, side, rest, shoulder, points[:, [s, e, w]], seen)
        rotation = None
        if hands and recording.has_component(HAND_COMPONENTS[side]):
            rotation, dofs = _fit_hand_of(body, recording, side, dofs)
        swivel = _swivel(shoulder, elbow_t, wrist_t, side)
        dofs = solve_arm(body, dofs, side, wrist_t, rotation, swivel)
        fitted = body.pose(dofs).positions_m
        for k, (target, part) in enumerate(
            ((shoulder, "shoulder"), (elbow_t, "elbow"), (wrist_t, "wrist"))
        ):
            miss = np.linalg.norm(fitted[:, _joint(body, side, part)] - target, axis=1) * 1000
            residual[:, 3 * column + k] = np.where(seen, miss, np.nan)
    if not fitted_any:
        raise PoseFileError("No arm was found in any frame (shoulder, elbow and wrist).")
    return ArmFit(dofs, residual, found, trunk, depth, _image_miss(body, dofs, image, found))


def _image_miss(body: BodyModel, dofs, recording: PoseRecording, found) -> np.ndarray | None:
    """Return how far the fitted arms' joints fall from the file's image landmarks
    (n_frames, 6), seen from the camera (x and y), in shoulder widths: both placed at
    their shoulders' midpoint. None without found image landmarks."""
    if not recording.found_component(POSE_COMPONENT):
        return None
    observed, _ = recording.component(POSE_COMPONENT, POSE_POINTS)
    positions = body.pose(dofs).positions_m
    fitted = to_mediapipe(positions[:, [body.skeleton.index(n.lower()) for n in POSE_POINTS]])

    def centred(points):  # (n, 6, 2), shoulder widths from the shoulders' midpoint
        xy = points[..., :2]
        shoulders = xy[:, [0, 3]]
        width = np.linalg.norm(shoulders[:, 0] - shoulders[:, 1], axis=-1).clip(1e-12)
        return (xy - shoulders.mean(axis=1, keepdims=True)) / width[:, None, None]

    miss = np.linalg.norm(centred(fitted) - centred(observed), axis=-1)
    return np.where(np.repeat(found, 3, axis=1), miss, np.nan)


def _nearest_seen(seen: np.ndarray) -> np.ndarray:
    """Return, per frame, the nearest frame (n,) where *seen* (n,) holds (ties: earlier).

    Linear in the frames (a long video's frames by its seen frames would not fit in
    memory).
    """
    seen_at = np.flatnonzero(seen)
    after = np.clip(np.searchsorted(seen_at, np.arange(len(seen))), 0, len(seen_at) - 1)
    before = np.clip(after - 1, 0, len(seen_at) - 1)
    frames = np.arange(len(seen))
    closer_before = np.abs(frames - seen_at[before]) <= np.abs(seen_at[after] - frames)
    return np.where(closer_before, seen_at[before], seen_at[after])


def _fit_trunk(body: BodyModel, recording: PoseRecording, component: str):
    """Return the trunk and head fitted to *component*'s points, or None if it has none
    of the head and hips (a file of arms only keeps the trunk at rest)."""
    names = dict(recording.components)[component]
    present = [name for name in BODY_POINTS if name in names]
    if not any(_names.index(name) in _HEAD_AND_HIPS for name in present):
        return None
    points, confidence = recording.component(component, tuple(present))
    full = np.zeros((recording.n_frames, len(BODY_POINTS), 3))
    seen = np.zeros((recording.n_frames, len(BODY_POINTS)))
    columns = [_names.index(name) for name in present]
    full[:, columns], seen[:, columns] = points, confidence
    return fit_trunk(body, full, seen)


def _swivel(shoulder: np.ndarray, elbow: np.ndarray, wrist: np.ndarray, side: str) -> np.ndarray:
    """Return the swivel angle (n,) that puts the IK's elbow where the observed one is.

    Measured as :func:`synthesis.rigs.ik.solve_arm` defines it: from straight down on
    the elbow's circle, positive away from the body.
    """
    n = wrist - shoulder
    n = n / np.linalg.norm(n, axis=1, keepdims=True).clip(1e-12)
    down = np.array([0.0, -1.0, 0.0]) + n[:, 1:2] * n
    vertical = np.linalg.norm(down, axis=1) < 1e-6
    down[vertical] = np.array([0.0, 0.0, 1.0]) - n[vertical, 2:3] * n[vertical]
    down = down / np.linalg.norm(down, axis=1, keepdims=True).clip(1e-12)
    outward = -1.0 if side == "right" else 1.0
    sideways = outward * np.cross(n, down)
    offset = elbow - shoulder
    return np.arctan2(np.sum(offset * sideways, axis=1), np.sum(offset * down, axis=1))
