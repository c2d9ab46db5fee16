"""Read a hand's letter against the shared reference of real human hands (issue 52).

``../shared/reference/asl-letter-landmarks/landmarks.npz``: 10,508 MediaPipe Hands samples
of the 26 letters (about 400 each, with depth; CC0, its README). A sample is placed in
pixels of its frame (16:9, as the palm's rigid bones say: the aspect that keeps their
lengths steadiest across the samples' orientations), mirrored as a selfie camera shows it,
and MediaPipe's depth scaled by 1.5 (by the same measure); then moved to the wrist and
scaled by the palm. A letter is read as the most common letter among the 15 nearest
reference samples: orientation counts (H is U turned sideways, P is K turned down).
"""

from pathlib import Path

import numpy as np
from scipy.spatial import cKDTree

REFERENCE = Path(__file__).resolve().parents[2] / "shared/reference/asl-letter-landmarks"
ASPECT, DEPTH_SCALE, K = 16 / 9, 1.5, 15
PALM = ((0, 5), (0, 17), (5, 17), (0, 9))


def features(points: np.ndarray) -> np.ndarray:
    """Return the features (n, 60) of hands (n, 21, 3) given in isotropic units."""
    points = points - points[:, :1]
    palm = np.mean([np.linalg.norm(points[:, a] - points[:, b], axis=1) for a, b in PALM], axis=0)
    return (points[:, 1:] / palm[:, None, None]).reshape(len(points), -1)


class ReferenceHands:
    """The reference samples, ready to read a hand's letter by its nearest neighbours."""

    def __init__(self, directory: Path = REFERENCE) -> None:
        data = np.load(directory / "landmarks.npz")
        raw = data["landmarks"].astype(np.float64)
        self.letters = data["letter"].astype(str)
        self.points = raw * np.array([ASPECT, 1.0, ASPECT * DEPTH_SCALE])
        self.tree = cKDTree(features(self.points))

    def read(self, hands: np.ndarray, exclude_self: bool = False) -> np.ndarray:
        """Return the letter read for each hand (n, 21, 3) in the reference's units."""
        k = K + 1 if exclude_self else K
        _, index = self.tree.query(features(hands), k=k)
        index = index[:, 1:] if exclude_self else index
        votes = self.letters[index]
        return np.array([max(set(row), key=list(row).count) for row in votes])


def from_mediapipe_px(marks_px: np.ndarray, width: int) -> np.ndarray:
    """Return MediaPipe's landmarks of our render (21, 3; x, y pixels, z as MediaPipe
    scales it times the width) in the reference's units: mirrored, depth scaled."""
    mirrored = np.array(marks_px, dtype=np.float64)
    mirrored[:, 0] = width - mirrored[:, 0]
    mirrored[:, 2] *= DEPTH_SCALE
    return mirrored
