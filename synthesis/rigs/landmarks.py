"""Export hand poses as the 21 MediaPipe hand landmarks (metres).

Order (MediaPipe Hands): 0 wrist; 1–4 thumb CMC, MCP, IP, tip; 5–8 index MCP, PIP, DIP,
tip; 9–12 middle; 13–16 ring; 17–20 pinky. Axes follow MediaPipe's world landmarks as
seen by the engine's default camera (looking along −z): x to the image's right, y down,
z away from the camera; the origin is the palm centre (mean of the wrist and the four
finger MCPs), like MediaPipe's "approximate geometric center of the hand".
"""

import numpy as np

from synthesis.rigs.hand import HandModel

LANDMARK_JOINTS = (
    "wrist",
    "thumb_cmc",
    "thumb_mcp",
    "thumb_ip",
    "thumb_tip",
    *(
        f"{finger}_{joint}"
        for finger in ("index", "middle", "ring", "pinky")
        for joint in ("mcp", "pip", "dip", "tip")
    ),
)
# MediaPipe's own names for the landmarks, in order.
LANDMARK_NAMES = (
    "WRIST",
    "THUMB_CMC",
    "THUMB_MCP",
    "THUMB_IP",
    "THUMB_TIP",
    *(
        f"{finger}_{joint}"
        for finger in ("INDEX_FINGER", "MIDDLE_FINGER", "RING_FINGER", "PINKY")
        for joint in ("MCP", "PIP", "DIP", "TIP")
    ),
)
PALM_CENTRE = (0, 5, 9, 13, 17)
# Engine world (x right, y up, z to the viewer) → MediaPipe (x right, y down, z away).
_TO_MEDIAPIPE = np.array([1.0, -1.0, -1.0])


def to_mediapipe(points: np.ndarray) -> np.ndarray:
    """Return engine-world points (..., 3) in MediaPipe's axes, or MediaPipe's in the
    engine's: the flip (y and z) is its own inverse."""
    return np.asarray(points, dtype=np.float64) * _TO_MEDIAPIPE


def landmarks(
    model: HandModel, dofs_rad: np.ndarray, bone_scale: np.ndarray | None = None
) -> np.ndarray:
    """Return landmarks (21, 3) for a DOF vector, or (n_frames, 21, 3) for (n_frames, n_dofs).

    *bone_scale* (n_joints,) as :meth:`synthesis.rigs.rig.Rig.pose` takes it.
    """
    dofs = np.asarray(dofs_rad, dtype=np.float64)
    positions = model.pose(dofs, bone_scale).positions_m
    index = [model.skeleton.index(name) for name in LANDMARK_JOINTS]
    points = to_mediapipe(positions[:, index])
    points = points - points[:, PALM_CENTRE].mean(axis=1, keepdims=True)
    return points[0] if dofs.ndim == 1 else points
