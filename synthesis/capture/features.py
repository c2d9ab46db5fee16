"""Describe a handshape by features that do not depend on where the hand is or how big.

The features of issue 16 ("handshapes against real signers"): the 15 finger-joint
flexion angles (three per digit, the angle between the bones meeting at the joint), the
10 fingertip-to-fingertip distances and the 5 fingertip-to-wrist distances, the
distances as a share of the wrist → middle-finger MCP length. Landmarks are MediaPipe's
21 hand points; for a file without depth, give them with z = 0 (the features are then
those of the image-plane projection).
"""

import numpy as np

# MediaPipe landmark indices: the wrist, then four per digit from the thumb.
WRIST, MIDDLE_MCP = 0, 9
TIPS = (4, 8, 12, 16, 20)
# Each digit's chain from the wrist: the angles are at its three inner points.
CHAINS = tuple((0, *range(1 + 4 * digit, 5 + 4 * digit)) for digit in range(5))
N_FEATURES = 15 + 10 + 5


def handshape_features(points: np.ndarray) -> np.ndarray:
    """Return the features (..., 30) of hand landmarks (..., 21, 3): angles in radians,
    then distances in palm lengths."""
    points = np.asarray(points, dtype=np.float64)
    angles = []
    for chain in CHAINS:
        for a, b, c in zip(chain, chain[1:], chain[2:], strict=False):
            first = points[..., b, :] - points[..., a, :]
            second = points[..., c, :] - points[..., b, :]
            cosine = np.sum(first * second, axis=-1) / np.maximum(
                np.linalg.norm(first, axis=-1) * np.linalg.norm(second, axis=-1), 1e-12
            )
            angles.append(np.arccos(np.clip(cosine, -1.0, 1.0)))
    palm = np.linalg.norm(points[..., MIDDLE_MCP, :] - points[..., WRIST, :], axis=-1)
    palm = np.maximum(palm, 1e-12)
    distances = [
        np.linalg.norm(points[..., i, :] - points[..., j, :], axis=-1) / palm
        for n, i in enumerate(TIPS)
        for j in TIPS[n + 1 :]
    ]
    distances += [
        np.linalg.norm(points[..., i, :] - points[..., WRIST, :], axis=-1) / palm for i in TIPS
    ]
    return np.stack(angles + distances, axis=-1)


def nearest_handshape(features: np.ndarray, references: dict[str, np.ndarray]) -> str:
    """Return the name of the reference whose features (30,) are nearest to *features*.

    Each feature column is scaled by its spread over the references, so angles and
    distances weigh alike.
    """
    names = list(references)
    table = np.stack([references[name] for name in names])
    spread = np.maximum(table.std(axis=0), 1e-9)
    distance = np.linalg.norm((table - np.asarray(features)) / spread, axis=1)
    return names[int(np.argmin(distance))]
