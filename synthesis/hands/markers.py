"""Virtual markers on the hand model, and ranking them (seed 000 ch. 3, App. A).

Seed 000 captured 13 markers on the hand with the lower forearm as the root link; every
marker position is expressed in the root's frame, so the arm's gross motion drops out.
Here the 13 markers sit on the hand model's joints: the thumb's MCP, IP and tip; the
index's MCP, PIP and tip; the middle and ring fingers' PIP and tip; the little
finger's MCP, PIP and tip. Two roots (``ROOTS``):

- ``"wrist"`` (the engine's hand technique): the wrist's own angles come with the arm's
  motion, so the markers carry the digits only and only the digits are reconstructed.
  The index and little-finger MCP markers sit on the wrist's rigid palm, so they never
  move in this frame: 2 of the 13 carry no information.
- ``"forearm"`` (seed 000 App. A, the paper's configuration): the lower forearm is the
  root link, so wrist flexion and deviation move every marker, the MCP markers on the
  back of the palm included, and the wrist is reconstructed with the digits.

Two ways to choose a sparse set of m markers: the PCA influence ranking (Alg. 2), whose
sets are nested (the best 6 hold the best 3), and the exhaustive search (Alg. 1) of
every m-marker combination by its nearest-pose error, a baseline for small m.
"""

import itertools

import numpy as np

MARKERS = (
    "thumb_mcp",
    "thumb_ip",
    "thumb_tip",
    "index_mcp",
    "index_pip",
    "index_tip",
    "middle_pip",
    "middle_tip",
    "ring_pip",
    "ring_tip",
    "pinky_mcp",
    "pinky_pip",
    "pinky_tip",
)
ROOT = "wrist"
ROOTS = ("wrist", "forearm")


def check_root(root: str) -> str:
    """Return *root*, or raise ValueError unless it is one of :data:`ROOTS`."""
    if root not in ROOTS:
        raise ValueError(f"The markers' root is {' or '.join(ROOTS)}, not {root!r}.")
    return root


def virtual_markers(hand, dofs_rad: np.ndarray, root: str = ROOT) -> np.ndarray:
    """Return the 13 markers (n_frames, 13, 3) in metres, in the root link's frame."""
    check_root(root)
    pose = hand.pose(np.atleast_2d(dofs_rad))
    skeleton = hand.skeleton
    root = skeleton.index(root)
    index = [skeleton.index(name) for name in MARKERS]
    rotation = pose.rotations[:, root]  # (n, 3, 3)
    offsets = pose.positions_m[:, index] - pose.positions_m[:, root, None]
    return np.einsum("nji,nkj->nki", rotation, offsets)


def pca(samples: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Return the mean (d,), eigenvalues (k,) descending and eigenvectors (d, k) of samples."""
    samples = np.asarray(samples, dtype=float)
    mean = samples.mean(axis=0)
    values, vectors = np.linalg.eigh(np.cov(samples - mean, rowvar=False))
    order = np.argsort(values)[::-1]
    return mean, np.clip(values[order], 0, None), vectors[:, order]


def marker_influence(coefficients: np.ndarray, eigenvalues: np.ndarray) -> np.ndarray:
    """Return each marker's influence: Σ over components and x/y/z of |coefficient × value|.

    Seed 000 Alg. 2. *coefficients*: (3·M, k) eigenvectors, a marker's x, y, z in rows
    3i, 3i + 1, 3i + 2; *eigenvalues*: (k,). Returns (M,).
    """
    weighted = np.abs(np.asarray(coefficients, float) * np.asarray(eigenvalues, float)[None, :])
    return weighted.sum(axis=1).reshape(-1, 3).sum(axis=1)


def rank_markers(markers: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Return the markers in order of PCA influence (most first) and their influences.

    *markers*: (n_frames, M, 3) positions relative to the root (Alg. 2). The best m are
    the first m: the sets are nested.
    """
    flat = np.asarray(markers, float).reshape(len(markers), -1)
    _, values, vectors = pca(flat)
    influence = marker_influence(vectors, values)
    return np.argsort(influence)[::-1], influence


def marker_distances(query: np.ndarray, database: np.ndarray) -> np.ndarray:
    """Return every marker's distance from each query frame to each database pose.

    (n_query, M, 3) and (p, M, 3) → (M, n_query, p), metres.
    """
    query, database = np.asarray(query, float), np.asarray(database, float)
    return np.stack(
        [
            np.linalg.norm(query[:, k, None, :] - database[None, :, k, :], axis=-1)
            for k in range(query.shape[1])
        ]
    )


def search_marker_sets(m: int, database: np.ndarray, test: np.ndarray) -> list[tuple]:
    """Return every m-marker set with its mean nearest-pose error, best first (Alg. 1).

    For each set, each test frame's nearest database pose is found by the summed
    distance of the set's markers; the frame's error is the mean distance of *all* the
    markers of that pose from the frame's (Table 3.1's measure: Alg. 1 read literally
    scores only the set's own markers, which favours markers that barely move). A set's
    error is the mean over the test frames, metres. Rows are ``(markers, error_m)``; the
    test sequence must not be part of the database.
    """
    distances = marker_distances(test, database)
    whole = distances.mean(axis=0)  # (n_test, p): every marker
    frames = np.arange(len(test))
    results = []
    for combination in itertools.combinations(range(database.shape[1]), m):
        nearest = distances[list(combination)].sum(axis=0).argmin(axis=1)
        results.append((combination, float(whole[frames, nearest].mean())))
    return sorted(results, key=lambda row: row[1])
