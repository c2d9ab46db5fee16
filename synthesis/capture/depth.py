"""Rebuild the depth of pose landmarks whose file flattened it (issue 54, item 3).

Some published ``.pose`` files carry one z for every point: spoken-to-signed's
fingerspelling lexicon has z = 250 ± 3 in POSE_LANDMARKS and POSE_WORLD_LANDMARKS
alike. An arm fitted to them lies in the image plane: a forearm raised toward the
camera came out pointing sideways and down, and a nose level with the ears turned the
head away. Where a file's depth is flat (:func:`flat_depth`), :func:`depth_from_lengths`
gives each arm segment the depth its length on the model asks for (|dz| = √(L² − l²),
*l* its length in the image at the shoulders' scale; the hand in front of the elbow and
the elbow in front of the shoulder, as in the signing space) and the head and hips the
depth the model has at rest. The image's x and y are kept as they are: the fit is then
checked against them (:attr:`synthesis.capture.armfit.ArmFit.image_miss`).
"""

from dataclasses import replace

import numpy as np

from synthesis.capture.posefile import PoseRecording
from synthesis.capture.trunkfit import BODY_POINTS, body_points
from synthesis.rigs.body import BodyModel
from synthesis.rigs.landmarks import to_mediapipe

# A file whose points' depths spread less than this share of the shoulder width, in
# its typical frame, has no depth (a real signer's nose is ~0.3 widths before the ears).
FLAT_DEPTH = 0.02
# The least confidence of an arm's point that counts it as seen.
MIN_CONFIDENCE = 0.2
ARM_POINTS = {
    side: tuple(f"{side.upper()}_{p}" for p in ("SHOULDER", "ELBOW", "WRIST"))
    for side in ("left", "right")
}
# A hand's points on the pose (MediaPipe's pose model): they take the wrist's depth.
_HAND_POINTS = ("PINKY", "INDEX", "THUMB")


def _shoulder_width(points: np.ndarray, names: tuple[str, ...]) -> np.ndarray:
    """Return each frame's shoulder width in the image (n,), x and y only."""
    left, right = names.index("LEFT_SHOULDER"), names.index("RIGHT_SHOULDER")
    return np.linalg.norm(points[:, left, :2] - points[:, right, :2], axis=-1)


def flat_depth(recording: PoseRecording, component: str) -> bool:
    """Return whether *component*'s depth is flat: in the median frame with both
    shoulders seen, its seen points' z spread under :data:`FLAT_DEPTH` shoulder widths."""
    names = dict(recording.components)[component]
    if not {"LEFT_SHOULDER", "RIGHT_SHOULDER"} <= set(names):
        return False
    points, confidence = recording.component(component)
    seen = confidence >= MIN_CONFIDENCE
    both = seen[:, names.index("LEFT_SHOULDER")] & seen[:, names.index("RIGHT_SHOULDER")]
    width = _shoulder_width(points, names)
    usable = both & (width > 0) & (seen.sum(axis=1) >= 3)
    if not usable.any():
        return False
    z = np.where(seen, points[..., 2], np.nan)[usable]
    spread = (np.nanmax(z, axis=1) - np.nanmin(z, axis=1)) / width[usable]
    return bool(np.median(spread) < FLAT_DEPTH)


def _rest_depths(body: BodyModel) -> dict[str, float]:
    """Return the model's rest depth of each BODY_POINT and arm joint, metres, MediaPipe's
    z (away from the camera), from the shoulders' midpoint."""
    rest = body.neutral()
    points = to_mediapipe(body_points(body, rest)[0])
    depths = dict(zip(BODY_POINTS, points[:, 2], strict=True))
    middle = (depths["LEFT_SHOULDER"] + depths["RIGHT_SHOULDER"]) / 2
    return {name: float(z - middle) for name, z in depths.items()}


def _length_m(rest: np.ndarray, body: BodyModel, a: str, b: str) -> float:
    """Return the distance between joints *a* and *b* of the model at rest, metres."""
    index = body.skeleton.index
    return float(np.linalg.norm(rest[index(a)] - rest[index(b)]))


def depth_from_lengths(recording: PoseRecording, component: str, body: BodyModel) -> PoseRecording:
    """Return *recording* with *component*'s z rebuilt from the model's proportions.

    Units stay the file's: the image's pixels per metre come from each frame's shoulder
    width against the model's. A segment longer in the image than on the model keeps
    no depth (its z difference is 0).
    """
    names = dict(recording.components)[component]
    points, _ = recording.component(component)
    points = points.copy()
    rest = body.pose(body.neutral()).positions_m[0]
    model_width = _length_m(rest, body, "left_shoulder", "right_shoulder")
    scale = _shoulder_width(points, names) / model_width  # file units per metre (n,)
    depths = _rest_depths(body)
    z = np.zeros(points.shape[:2])
    for name in names:
        if name in depths:
            z[:, names.index(name)] = depths[name] * scale
    for side, (shoulder, elbow, wrist) in ARM_POINTS.items():
        if not {shoulder, elbow, wrist} <= set(names):
            continue
        upper_m = _length_m(rest, body, f"{side}_shoulder", f"{side}_elbow")
        fore_m = _length_m(rest, body, f"{side}_elbow", f"{side}_wrist")
        s, e, w = (names.index(n) for n in (shoulder, elbow, wrist))
        for start, end, length_m in ((s, e, upper_m), (e, w, fore_m)):
            seen_m = np.linalg.norm(points[:, end, :2] - points[:, start, :2], axis=-1)
            forward = np.sqrt(np.clip((length_m * scale) ** 2 - seen_m**2, 0.0, None))
            z[:, end] = z[:, start] - forward  # toward the camera: smaller z
        for part in _HAND_POINTS:
            if f"{side.upper()}_{part}" in names:
                z[:, names.index(f"{side.upper()}_{part}")] = z[:, w]
    points[..., 2] = z
    offset = 0
    for name, point_names in recording.components:
        if name == component:
            break
        offset += len(point_names)
    everything = recording.points.copy()
    everything[:, offset : offset + len(names)] = points
    return replace(recording, points=everything)


__all__ = ["ARM_POINTS", "FLAT_DEPTH", "MIN_CONFIDENCE", "depth_from_lengths", "flat_depth"]
