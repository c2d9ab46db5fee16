"""Measure how a camera frames an avatar's hands and head, from the projected mesh.

Issue 16's framing targets are stated in pixels of the rendered frame: the hand's
height as a share of the frame's in the close-up, no hand vertex outside the frame in
any frame, the face's height in the signing view (measured here as the head's: the
avatar has no face yet). The posed skin is projected through the camera preset as the
renderer's perspective camera sees it (vertical field of view, the frame's aspect), and
each part's vertices are told by the joint that weighs most on them (the hands: wrist
and finger joints; the head: the head joint).
"""

from dataclasses import dataclass

import numpy as np

from synthesis.avatar.model import Avatar
from synthesis.render.scene import CameraPath, CameraPreset, project_px
from synthesis.rigs.face import FACE_JOINT_NAMES
from synthesis.rigs.hand import HandModel
from synthesis.skeleton.kinematics import Pose

# The hand's joints, as the hand model names them (a body's are these behind a side).
HAND_JOINTS = tuple(name for name in HandModel().skeleton.names if name != "forearm")

__all__ = ["HAND_JOINTS", "Framing", "hand_vertices", "measure_framing", "project_px"]


def _owned(avatar: Avatar, wanted) -> list[np.ndarray]:
    """Return, per part, which vertices (n,) are owned most by a joint that *wanted* takes."""
    taken = np.array([wanted(name) for name in avatar.rig.skeleton.names], dtype=bool)
    return [taken[part.weights.main_joints()] for part in avatar.parts]


def _is_hand(name: str) -> bool:
    return any(name == joint or name.endswith("_" + joint) for joint in HAND_JOINTS)


@dataclass(frozen=True)
class Framing:
    """Per frame: the hands' bounding box height over the frame's (*hand_share*), whether
    any hand vertex lies outside the frame (*hand_outside*), the head's bounding box
    height in pixels, crown to chin (*head_px*; NaN for an avatar without a head), and
    the face's, brows to chin (*face_px*: what the face's bones move)."""

    hand_share: np.ndarray
    hand_outside: np.ndarray
    head_px: np.ndarray
    face_px: np.ndarray | None = None

    def to_dict(self) -> dict:
        return {
            "hand_share_min": float(np.min(self.hand_share)),
            "hand_share_median": float(np.median(self.hand_share)),
            "frames_hand_outside": int(self.hand_outside.sum()),
            "head_px_min": _least(self.head_px),
            "face_px_min": _least(self.face_px),
            "n_frames": len(self.hand_share),
        }


def _least(values: np.ndarray | None) -> float | None:
    if values is None or not np.isfinite(values).any():
        return None
    return float(np.nanmin(values))


def _posed(avatar: Avatar, motion: np.ndarray | Pose, masks: list[np.ndarray]) -> np.ndarray:
    """Return the vertices that *masks* (per part) pick, posed: (n_frames, n, 3) m."""
    pose = motion if isinstance(motion, Pose) else avatar.rig.pose(np.atleast_2d(motion))
    return np.concatenate([vertices for vertices, _ in avatar.deform_pose(pose, masks)], axis=1)


def _take(motion: np.ndarray | Pose, frames) -> np.ndarray | Pose:
    """Return some frames (a slice or indices) of DOF vectors or a Pose."""
    if isinstance(motion, Pose):
        return Pose(motion.quaternions[frames], motion.positions_m[frames])
    return np.atleast_2d(motion)[frames]


def hand_vertices(avatar: Avatar, motion: np.ndarray | Pose, batch: int = 64) -> np.ndarray:
    """Return the posed hands' vertices (n_frames, n, 3) m for DOF vectors or a Pose,
    posing only the hands' vertices, *batch* frames at a time (all at once is slower:
    every frame's arrays)."""
    masks = _owned(avatar, _is_hand)
    total = motion.quaternions.shape[0] if isinstance(motion, Pose) else len(np.atleast_2d(motion))
    return np.concatenate(
        [_posed(avatar, _take(motion, slice(k, k + batch)), masks) for k in range(0, total, batch)]
    )


def _project(
    camera: CameraPreset | CameraPath, points_m: np.ndarray, width: int, height: int
) -> np.ndarray:
    """Project points (n_frames, n, 3) through a camera, or frame by frame a path's."""
    if isinstance(camera, CameraPreset):
        return project_px(camera, points_m, width, height)
    return np.stack(
        [project_px(camera.at(k), frame, width, height) for k, frame in enumerate(points_m)]
    )


def measure_framing(
    avatar: Avatar,
    camera: CameraPreset | CameraPath,
    dofs_rad: np.ndarray | Pose,
    width: int = 640,
    height: int = 480,
    frames: np.ndarray | None = None,
) -> Framing:
    """Return how *camera* (one, or a path of one per frame) frames *avatar* posed by
    *dofs_rad* (n_frames, n_dofs) or a Pose, at *width* × *height*; *frames* (indices)
    picks the frames to measure (all by default)."""
    motion = dofs_rad if isinstance(dofs_rad, Pose) else np.atleast_2d(dofs_rad)
    if frames is not None:
        frames = np.asarray(frames)
        motion = _take(motion, frames)
        if isinstance(camera, CameraPath):
            camera = camera.take(frames)
    if not isinstance(motion, Pose):
        motion = avatar.rig.pose(motion)  # posed once for the hands, the head and the face
    hand = _posed(avatar, motion, _owned(avatar, _is_hand))
    pixels = _project(camera, hand, width, height)
    share = (np.nanmax(pixels[..., 1], axis=1) - np.nanmin(pixels[..., 1], axis=1)) / height
    outside = (
        (pixels[..., 0] < 0)
        | (pixels[..., 0] > width)
        | (pixels[..., 1] < 0)
        | (pixels[..., 1] > height)
        | np.isnan(pixels).any(axis=-1)
    ).any(axis=1)
    heights = []
    head = _owned(avatar, lambda name: name == "head" or name in FACE_JOINT_NAMES)
    for masks in (head, face_vertices(avatar)):
        points = _posed(avatar, motion, masks)
        if points.shape[1]:
            y = _project(camera, points, width, height)[..., 1]
            heights.append(np.nanmax(y, axis=1) - np.nanmin(y, axis=1))
        else:
            heights.append(np.full(len(hand), np.nan))
    return Framing(share, outside, *heights)


# The face of an avatar whose face moves by blendshapes (no face bones): the head's skin
# in front of the ears, from the chin to the forehead (below the hairline, as far up as
# MediaPipe's face mesh reaches), measured from the eyes' centres.
FOREHEAD_ABOVE_EYES_M, EARS_BEHIND_EYES_M = 0.045, 0.05


def face_vertices(avatar: Avatar) -> list[np.ndarray]:
    """Return, per part, the face's vertices: those the face's bones carry (brows to chin),
    or on an avatar whose face moves by blendshapes, the head's skin before the ears from
    the chin to the forehead."""
    if avatar.drive is None:
        return _owned(avatar, lambda name: name in FACE_JOINT_NAMES)
    head = _owned(avatar, lambda name: name == "head")
    names = avatar.rig.skeleton.names
    bind = avatar.bind_pose.positions_m[0]
    eyes = (bind[names.index("right_eye")] + bind[names.index("left_eye")]) / 2
    return [
        mask
        & (part.vertices_m[:, 1] < eyes[1] + FOREHEAD_ABOVE_EYES_M)
        & (part.vertices_m[:, 2] > eyes[2] - EARS_BEHIND_EYES_M)
        for mask, part in zip(head, avatar.parts, strict=True)
    ]
