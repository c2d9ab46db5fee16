"""Write landmarks as the clip's camera films them (MediaPipe Holistic's conventions).

A ``.pose`` file a researcher opens beside the clip should lay over it: x and y are
pixels of the clip's frame (x right, y down), z the depth from a reference point in the
same pixel scale as x, smaller toward the camera, as MediaPipe's image landmarks give
it (the body's from the hips' midpoint, a hand's from its wrist). A body's pose points
also come as ``POSE_WORLD_LANDMARKS``: metres from the hips' midpoint in MediaPipe's
axes, Holistic's metric pose, which the engine's own fit prefers (issue 54, item 4).
"""

import numpy as np

from synthesis.capture.armfit import BODY_COMPONENTS, body_landmarks_m
from synthesis.capture.posefile import (
    HAND_COMPONENTS,
    POSE_COMPONENT,
    POSE_WORLD_COMPONENT,
    PoseRecording,
)
from synthesis.render.scene import CameraPath, CameraPreset, project_with_depth
from synthesis.rigs.body import BodyModel
from synthesis.rigs.hand import HandModel
from synthesis.rigs.landmarks import LANDMARK_JOINTS, LANDMARK_NAMES, to_mediapipe


def filmed_body_motion(
    body: BodyModel,
    dofs_rad: np.ndarray,
    rate_hz: float,
    camera: CameraPreset | CameraPath,
    width: int,
    height: int,
) -> PoseRecording:
    """Return body DOFs (n_frames, n_dofs) as the clip's camera films their landmarks
    (:func:`synthesis.capture.armfit.body_landmarks_m`), z from the hips' midpoint."""
    world = body_landmarks_m(body, dofs_rad)
    names = dict(BODY_COMPONENTS)[POSE_COMPONENT]
    hips = world[:, [names.index("LEFT_HIP"), names.index("RIGHT_HIP")]].mean(axis=1)
    return filmed_recording(BODY_COMPONENTS, world, hips, rate_hz, camera, width, height)


def filmed_hand_motion(
    model: HandModel,
    dofs_rad: np.ndarray,
    rate_hz: float,
    camera: CameraPreset | CameraPath,
    width: int,
    height: int,
) -> PoseRecording:
    """Return a hand's DOFs (n_frames, n_dofs) as the close-up's camera films its 21
    landmarks, z from the wrist."""
    positions = model.pose(np.atleast_2d(dofs_rad)).positions_m
    world = positions[:, [model.skeleton.index(joint) for joint in LANDMARK_JOINTS]]
    components = ((HAND_COMPONENTS[model.side], LANDMARK_NAMES),)
    return filmed_recording(components, world, world[:, 0], rate_hz, camera, width, height)


def filmed_recording(
    components: tuple[tuple[str, tuple[str, ...]], ...],
    world_m: np.ndarray,
    origin_m: np.ndarray,
    rate_hz: float,
    camera: CameraPreset | CameraPath,
    width: int,
    height: int,
) -> PoseRecording:
    """Return landmarks *world_m* (n_frames, k, 3; engine axes, metres) of *components*
    as *camera* films them in a *width* × *height* clip, z from *origin_m* (n_frames, 3).

    A point behind the camera is unfound (confidence 0).
    """
    world = np.asarray(world_m, dtype=np.float64)
    origin = np.asarray(origin_m, dtype=np.float64)
    n_frames = len(world)
    pixels = np.empty((*world.shape[:2], 2))
    depth = np.empty(world.shape[:2])
    reference = np.empty(n_frames)
    for frame in range(n_frames):
        seen_by = _camera_at(camera, frame)
        # The points and the reference in one projection (the camera inverted once).
        both = np.vstack([world[frame], origin[frame]])
        seen, distance = project_with_depth(seen_by, both, width, height)
        pixels[frame], depth[frame], reference[frame] = seen[:-1], distance[:-1], distance[-1]
    # A depth difference seen at the reference's distance, in pixels (pinhole camera).
    focal_px = height / (2 * np.tan(np.radians(camera.yfov_deg) / 2))
    z = (depth - reference[:, None]) * focal_px / reference[:, None]
    points = np.concatenate([pixels, z[..., None]], axis=-1)
    found = np.isfinite(points).all(axis=-1)
    points[~found] = 0.0
    confidence = found.astype(np.float64)
    offset = 0
    for name, names in components:
        if name == POSE_COMPONENT:
            pose = world[:, offset : offset + len(names)] - origin[:, None]
            components = (*components, (POSE_WORLD_COMPONENT, names))
            points = np.concatenate([points, to_mediapipe(pose)], axis=1)
            confidence = np.concatenate([confidence, np.ones(pose.shape[:2])], axis=1)
            break
        offset += len(names)
    return PoseRecording(float(rate_hz), components, points, confidence, width, height)


def _camera_at(camera: CameraPreset | CameraPath, frame: int) -> CameraPreset:
    """Return the camera that films *frame* (a moving camera's, or the still one)."""
    if isinstance(camera, CameraPath):
        return camera.at(min(frame, len(camera) - 1))
    return camera
