"""Evaluate sparse-marker reconstruction like seed 000 Table 3.1 and compare marker choices.

Table 3.1 gives the mean marker error (cm) by pose-database size p and marker count m
for the nearest-pose method. Two configurations:

- **the engine's** (:func:`table_3_1`): the test motion is the engine's spelling of
  words that are not in the database (the alphabet); markers are chosen by PCA
  influence (Alg. 2) and rooted at the wrist, as the hand technique uses them;
- **the paper's** (:func:`paper_table_3_1`, seed 000 §3.1): markers rooted at the lower
  forearm (App. A), chosen by the exhaustive search (Alg. 1) for each p and m, from a
  database of varied hand motion, tested on a sequence withheld from it (:class:`HeldOut`:
  simulated gestures, or the human letters with some letters withheld).
"""

import numpy as np

from synthesis.hands.heldout import HeldOut
from synthesis.hands.markers import MARKERS, rank_markers, search_marker_sets, virtual_markers
from synthesis.hands.reconstruct import PoseDatabase, marker_error_cm, reconstruct_nearest

ENGINE_CONFIGURATION = "engine: Alg. 2 markers, wrist root, words spelled from its letters"
PAPER_CONFIGURATION = "seed 000 §3.1: Alg. 1 markers per p and m, forearm root, held-out test"
PUBLISHED_INPUT = "Vicon capture of conversational gestures, over 10,000 frames at 120 Hz"

# Seed 000 Table 3.1: mean (s.d.) marker error in cm, by p and m ("Full" = all 13).
PUBLISHED_TABLE_3_1 = {
    50: {2: (1.2, 0.38), 4: (1.1, 0.31), 6: (1.1, 0.32), 13: (1.0, 0.27)},
    100: {2: (1.1, 0.32), 4: (1.3, 0.40), 6: (0.88, 0.21), 13: (0.86, 0.19)},
    500: {2: (1.0, 0.57), 4: (1.0, 0.54), 6: (0.68, 0.23), 13: (0.65, 0.21)},
    1000: {2: (0.88, 0.27), 4: (0.80, 0.35), 6: (0.65, 0.23), 13: (0.62, 0.20)},
}


def _row(configuration: str, source: str, poses: int, chosen, truth, rebuilt, hand, root):
    mean, spread = marker_error_cm(truth, virtual_markers(hand, rebuilt, root))
    paper_mean, paper_sd = PUBLISHED_TABLE_3_1.get(poses, {}).get(len(chosen), (None, None))
    return {
        "configuration": configuration,
        "input": source,
        "poses": poses,
        "markers": len(chosen),
        "set": " ".join(MARKERS[i] for i in sorted(chosen)),
        "error_cm": round(mean, 3),
        "sd_cm": round(spread, 3),
        "published_cm": paper_mean,
        "published_sd_cm": paper_sd,
        "published_input": PUBLISHED_INPUT,
    }


def table_3_1(
    database: PoseDatabase,
    hand,
    test_dofs: np.ndarray,
    rate_hz: float,
    rng: np.random.Generator,
    source: str = "",
    poses=(50, 100, 500, 1000),
    sizes=(2, 4, 6),
) -> list[dict]:
    """Return Table 3.1's rows for the nearest-pose method on *test_dofs* (hand DOFs), in
    the engine's configuration; *source* says what the test motion is."""
    truth = virtual_markers(hand, test_dofs, database.root)
    order = rank_markers(database.markers)[0]
    source = source or database.source
    rows = []
    for p in poses:
        clustered = database.clustered(p, rng)
        for markers in (*sizes, len(MARKERS)):
            chosen = order[:markers]
            rebuilt = reconstruct_nearest(truth[:, chosen], chosen, clustered, rate_hz)
            rows.append(
                _row(ENGINE_CONFIGURATION, source, p, chosen, truth, rebuilt, hand, database.root)
            )
    return rows


def paper_table_3_1(
    held_out: HeldOut,
    hand,
    rate_hz: float,
    rng: np.random.Generator,
    poses=(50, 100, 500, 1000),
    sizes=(2, 4, 6),
    select_on: str = "selection",
    selection_stride: int = 4,
) -> list[dict]:
    """Return Table 3.1's rows in seed 000 §3.1's configuration.

    For each database size p (k-means over all 13 markers, §3.1.2) and marker count m,
    the m markers are chosen by the exhaustive search (Alg. 1) on the selection sequence
    (every *selection_stride*-th frame, for speed), or on the test sequence itself when
    *select_on* is ``"test"`` (Alg. 1 read literally: the paper's search used its test
    sequence); the full set ("Full", m = 13) is added. Each frame of the test sequence is
    rebuilt from its nearest pose by the chosen markers; the error is the mean distance
    of all 13 markers, rooted at the database's root.
    """
    if select_on not in ("selection", "test"):
        raise ValueError(f"select_on is 'selection' or 'test', not {select_on!r}.")
    root = held_out.database.root
    truth = virtual_markers(hand, held_out.test_dofs, root)
    chooser = held_out.test_dofs if select_on == "test" else held_out.selection_dofs
    choosing = virtual_markers(hand, chooser[::selection_stride], root)
    rows = []
    for p in poses:
        clustered = held_out.database.clustered(p, rng)
        for m in (*sizes, len(MARKERS)):
            chosen = search_marker_sets(m, clustered.markers, choosing)[0][0]
            rebuilt = reconstruct_nearest(truth[:, chosen], chosen, clustered, rate_hz)
            rows.append(
                _row(PAPER_CONFIGURATION, held_out.input, p, chosen, truth, rebuilt, hand, root)
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
