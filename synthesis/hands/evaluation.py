"""Evaluate sparse-marker reconstruction like seed 000 Table 3.1 and compare marker choices.

Table 3.1 gives the mean marker error (cm) by pose-database size p and marker count m
for the nearest-pose method. Here the test motion is the engine's spelling of words
that are not in the database (the alphabet); markers are chosen by PCA influence, and
the exhaustive search (Alg. 1) is run beside it for small m.
"""

import numpy as np

from synthesis.hands.markers import MARKERS, rank_markers, search_marker_sets, virtual_markers
from synthesis.hands.reconstruct import PoseDatabase, marker_error_cm, reconstruct_nearest

# Seed 000 Table 3.1: mean (s.d.) marker error in cm, by p and m ("Full" = all 13).
PUBLISHED_TABLE_3_1 = {
    50: {2: (1.2, 0.38), 4: (1.1, 0.31), 6: (1.1, 0.32), 13: (1.0, 0.27)},
    100: {2: (1.1, 0.32), 4: (1.3, 0.40), 6: (0.88, 0.21), 13: (0.86, 0.19)},
    500: {2: (1.0, 0.57), 4: (1.0, 0.54), 6: (0.68, 0.23), 13: (0.65, 0.21)},
    1000: {2: (0.88, 0.27), 4: (0.80, 0.35), 6: (0.65, 0.23), 13: (0.62, 0.20)},
}


def table_3_1(
    database: PoseDatabase, hand, test_dofs: np.ndarray, rate_hz: float, rng: np.random.Generator
) -> list[dict]:
    """Return Table 3.1's rows for the nearest-pose method on *test_dofs* (hand DOFs)."""
    truth = virtual_markers(hand, test_dofs)
    order = rank_markers(database.markers)[0]
    rows = []
    for poses, published in PUBLISHED_TABLE_3_1.items():
        clustered = database.clustered(poses, rng)
        for markers, (paper_mean, paper_sd) in published.items():
            chosen = order[:markers]
            rebuilt = reconstruct_nearest(truth[:, chosen], chosen, clustered, rate_hz)
            mean, spread = marker_error_cm(truth, virtual_markers(hand, rebuilt))
            rows.append(
                {
                    "poses": poses,
                    "markers": markers,
                    "error_cm": round(mean, 3),
                    "sd_cm": round(spread, 3),
                    "published_cm": paper_mean,
                    "published_sd_cm": paper_sd,
                }
            )
    return rows


def compare_marker_choices(
    database: PoseDatabase,
    hand,
    test_dofs: np.ndarray,
    rng: np.random.Generator,
    sizes=(2, 3),
    poses: int = 200,
) -> list[dict]:
    """Return, per m, the PCA-ranked set and the exhaustive search's best set (Alg. 1)
    with each one's nearest-pose error (cm) on *test_dofs*."""
    truth = virtual_markers(hand, test_dofs)
    clustered = database.clustered(poses, rng)
    order = rank_markers(database.markers)[0]
    rows = []
    for m in sizes:
        searched = search_marker_sets(m, clustered.markers, truth)
        errors = dict(searched)
        pca_set = tuple(sorted(int(i) for i in order[:m]))
        best, best_error = searched[0]
        rows.append(
            {
                "markers": m,
                "method": "PCA influence (Alg. 2)",
                "set": " ".join(MARKERS[i] for i in pca_set),
                "error_cm": round(100 * errors[pca_set], 3),
            }
        )
        rows.append(
            {
                "markers": m,
                "method": "exhaustive search (Alg. 1)",
                "set": " ".join(MARKERS[i] for i in best),
                "error_cm": round(100 * best_error, 3),
            }
        )
    return rows
