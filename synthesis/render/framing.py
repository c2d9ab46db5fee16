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
from synthesis.render.scene import CameraPreset
from synthesis.rigs.hand import HandModel

# The hand's joints, as the hand model names them (a body's are these behind a side).
HAND_JOINTS = tuple(name for name in HandModel().skeleton.names if name != "forearm")


def project_px(camera: CameraPreset, points_m: np.ndarray, width: int, height: int) -> np.ndarray:
    """Return image coordinates (..., 2) in pixels (x right, y down) of world points (..., 3).

    Points behind the camera come out as NaN.
    """
    to_camera = np.linalg.inv(camera.pose())
    points = np.asarray(points_m, dtype=np.float64) @ to_camera[:3, :3].T + to_camera[:3, 3]
    depth = -points[..., 2]
    with np.errstate(divide="ignore", invalid="ignore"):
        focal = 1.0 / np.tan(np.radians(camera.yfov_deg) / 2)
        x_ndc = np.where(depth > 0, points[..., 0] / depth * focal * height / width, np.nan)
        y_ndc = np.where(depth > 0, points[..., 1] / depth * focal, np.nan)
    return np.stack([(x_ndc + 1) / 2 * width, (1 - y_ndc) / 2 * height], axis=-1)


def _owned(avatar: Avatar, wanted) -> list[np.ndarray]:
    """Return, per part, which vertices (n,) are owned most by a joint that *wanted* takes."""
    names = avatar.rig.skeleton.names
    masks = []
    for part in avatar.parts:
        owner = part.weights.joints[np.arange(len(part.weights.joints)),
                                    part.weights.weights.argmax(axis=1)]  # fmt: skip
        masks.append(np.array([wanted(names[j]) for j in owner], dtype=bool))
    return masks


def _is_hand(name: str) -> bool:
    return any(name == joint or name.endswith("_" + joint) for joint in HAND_JOINTS)


@dataclass(frozen=True)
class Framing:
    """Per frame: the hands' bounding box height over the frame's (*hand_share*), whether
    any hand vertex lies outside the frame (*hand_outside*), and the head's bounding box
    height in pixels (*head_px*; NaN for an avatar without a head)."""

    hand_share: np.ndarray
    hand_outside: np.ndarray
    head_px: np.ndarray

    def to_dict(self) -> dict:
        return {
            "hand_share_min": float(np.min(self.hand_share)),
            "hand_share_median": float(np.median(self.hand_share)),
            "frames_hand_outside": int(self.hand_outside.sum()),
            "head_px_min": float(np.nanmin(self.head_px)) if np.isfinite(self.head_px).any()
            else None,
            "n_frames": len(self.hand_share),
        }  # fmt: skip


def measure_framing(
    avatar: Avatar, camera: CameraPreset, dofs_rad: np.ndarray, width: int = 640,
    height: int = 480, frames: np.ndarray | None = None,
) -> Framing:  # fmt: skip
    """Return how *camera* frames *avatar* posed by *dofs_rad* (n_frames, n_dofs), at
    *width* × *height*; *frames* (indices) picks the frames to measure (all by default)."""
    dofs = np.atleast_2d(dofs_rad)
    if frames is not None:
        dofs = dofs[np.asarray(frames)]
    posed = [vertices for vertices, _ in avatar.deform(dofs)]
    hands, heads = _owned(avatar, _is_hand), _owned(avatar, lambda name: name == "head")
    hand = np.concatenate([v[:, m] for v, m in zip(posed, hands, strict=True)], axis=1)
    pixels = project_px(camera, hand, width, height)
    share = (np.nanmax(pixels[..., 1], axis=1) - np.nanmin(pixels[..., 1], axis=1)) / height
    outside = ((pixels[..., 0] < 0) | (pixels[..., 0] > width) | (pixels[..., 1] < 0)
               | (pixels[..., 1] > height) | np.isnan(pixels).any(axis=-1)).any(axis=1)  # fmt: skip
    head = np.concatenate([v[:, m] for v, m in zip(posed, heads, strict=True)], axis=1)
    if head.shape[1]:
        head_y = project_px(camera, head, width, height)[..., 1]
        head_px = np.nanmax(head_y, axis=1) - np.nanmin(head_y, axis=1)
    else:
        head_px = np.full(len(dofs), np.nan)
    return Framing(share, outside, head_px)
