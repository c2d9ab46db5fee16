"""Measure what a viewer sees of the hands and the face: each hand's size in pixels,
whether it leaves the frame, and how much of the face a hand hides.

A signer's hand whose skin leaves the frame through its bottom edge alone is
*lowered*: the signing view is framed from above the head to the waist, the lower edge
of the signing space (Battison 1978; Klima & Bellugi 1979), so a hand below it rests at
the side and signs nothing. A hand out through a side or the top, or partly behind the
camera, is *outside*; so is a lone hand (the close-up's) out through any edge.

The posed skin is projected through the clip's camera as the renderer sees it
(:mod:`synthesis.render.framing` tells the parts' vertices by the joint that weighs
most on them). A face vertex counts as hidden when a hand's skin lies over its pixel
nearer the camera: the hands are drawn into a coarse depth buffer (one cell per
:data:`CELL_PX` pixels, the nearest hand depth in each), and each face vertex is
compared with its cell.
"""

from dataclasses import dataclass

import numpy as np

from synthesis.avatar.model import Avatar
from synthesis.render.framing import HAND_JOINTS, face_vertices
from synthesis.render.scene import CameraPath, CameraPreset, project_with_depth
from synthesis.skeleton.kinematics import Pose

# A hand's skin is sampled a vertex apart (≤ 6 mm on the human signer, under 4 px at
# 720p in the signing view); cells of 4 px leave no gap between projected samples.
CELL_PX = 4


@dataclass(frozen=True)
class Visibility:
    """Per frame and hand (sides in *hands*): the hand's box in pixels, the larger of its
    width and height (*hand_px*, (n_frames, n_hands)), whether any of its skin lies
    outside the frame through a side or the top (*outside*) or through the bottom edge
    alone (*lowered*); the share of the face's vertices a hand hides (*face_hidden*,
    (n_frames,); None without a face)."""

    hands: tuple[str, ...]
    hand_px: np.ndarray
    outside: np.ndarray
    lowered: np.ndarray
    face_hidden: np.ndarray | None


def _hand_side(name: str, sides: tuple[str, ...]) -> str | None:
    """Return the side whose hand *name* belongs to ("" for a lone hand), or None."""
    for side in sides:
        prefix = f"{side}_" if side else ""
        if name.startswith(prefix) and name[len(prefix) :] in HAND_JOINTS:
            return side
    return None


def _masks(avatar: Avatar, side: str, sides: tuple[str, ...]) -> list[np.ndarray]:
    """Return, per part, which vertices the hand of *side* owns most."""
    owned = np.array([_hand_side(n, sides) == side for n in avatar.rig.skeleton.names])
    return [owned[part.weights.main_joints()] for part in avatar.parts]


def hand_sides(avatar: Avatar) -> tuple[str, ...]:
    """Return the sides of the avatar's hands: ("right", "left"), or ("",) for a lone hand."""
    names = avatar.rig.skeleton.names
    sides = tuple(side for side in ("right", "left") if f"{side}_wrist" in names)
    return sides or ("",)


def _per_frame(camera, points_m: np.ndarray, width: int, height: int):
    """Project points (n_frames, n, 3) through a camera or, frame by frame, a path's."""
    if isinstance(camera, CameraPreset):
        return project_with_depth(camera, points_m, width, height)
    projected = [
        project_with_depth(camera.at(k), frame, width, height) for k, frame in enumerate(points_m)
    ]
    return np.stack([p for p, _ in projected]), np.stack([d for _, d in projected])


def _hidden_share(hand_px, hand_depth, face_px, face_depth, width, height) -> np.ndarray:
    """Return, per frame, the share of face points behind a hand's skin (depth buffer)."""
    n_frames = len(face_px)
    cols, rows = -(-width // CELL_PX), -(-height // CELL_PX)
    nearest = np.full((n_frames, rows * cols), np.inf)
    frame = np.broadcast_to(np.arange(n_frames)[:, None], hand_depth.shape)
    cell = _cells(hand_px, cols, rows)
    ok = cell >= 0
    np.minimum.at(nearest, (frame[ok], cell[ok]), hand_depth[ok])
    face_cell = _cells(face_px, cols, rows)
    seen = face_cell >= 0
    in_front = np.take_along_axis(nearest, np.maximum(face_cell, 0), axis=1)
    hidden = seen & (in_front < face_depth)
    return hidden.sum(axis=1) / np.maximum(seen.sum(axis=1), 1)


def _cells(pixels: np.ndarray, cols: int, rows: int) -> np.ndarray:
    """Return each pixel's cell index (−1 outside the frame or behind the camera)."""
    with np.errstate(invalid="ignore"):
        col = np.floor(pixels[..., 0] / CELL_PX)
        row = np.floor(pixels[..., 1] / CELL_PX)
        inside = (col >= 0) & (col < cols) & (row >= 0) & (row < rows)
    return np.where(inside, np.nan_to_num(row) * cols + np.nan_to_num(col), -1).astype(np.intp)


def measure_visibility(
    avatar: Avatar, camera: CameraPreset | CameraPath, pose: Pose, width: int, height: int
) -> Visibility:
    """Return what the camera shows of *avatar*'s hands and face posed by *pose*."""
    sides = hand_sides(avatar)
    sizes, outside, lowered, hand_points, hand_depths = [], [], [], [], []
    for side in sides:
        posed = np.concatenate(
            [v for v, _ in avatar.deform_pose(pose, _masks(avatar, side, sides))], axis=1
        )
        pixels, depth = _per_frame(camera, posed, width, height)
        if not posed.shape[1]:
            # An imported avatar whose skin no hand joint owns: nothing to measure.
            sizes.append(np.full(len(posed), np.nan))
            outside.append(np.zeros(len(posed), dtype=bool))
            lowered.append(np.zeros(len(posed), dtype=bool))
            continue
        extent = np.nanmax(pixels, axis=1) - np.nanmin(pixels, axis=1)
        sizes.append(extent.max(axis=1))
        x, y = pixels[..., 0], pixels[..., 1]
        # Pixels' y runs down the frame: past the height is below its bottom edge. A lone
        # hand has no body to rest beside: below the frame is outside it.
        below = (y > height).any(axis=1)
        elsewhere = ((x < 0) | (x > width) | (y < 0) | np.isnan(x) | np.isnan(y)).any(axis=1)
        if not side:
            elsewhere |= below
        outside.append(elsewhere)
        lowered.append(below & ~elsewhere)
        hand_points.append(pixels)
        hand_depths.append(depth)
    face_hidden = None
    face = np.concatenate([v for v, _ in avatar.deform_pose(pose, face_vertices(avatar))], axis=1)
    if face.shape[1] and hand_points:
        face_px, face_depth = _per_frame(camera, face, width, height)
        face_hidden = _hidden_share(
            np.concatenate(hand_points, axis=1),
            np.concatenate(hand_depths, axis=1),
            face_px,
            face_depth,
            width,
            height,
        )
    return Visibility(
        sides,
        np.stack(sizes, axis=1),
        np.stack(outside, axis=1),
        np.stack(lowered, axis=1),
        face_hidden,
    )
