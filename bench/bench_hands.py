"""Measure issue 18's figures: DOF reduction, marker ranking, reconstruction throughput.

Issue 18 names no targets; it asks for the reduction of a 60 s two-hand recording at 30
fps, reconstruction throughput (frames/s), the PCA ranking time, and the errors. The
"recording" is the engine's own: its story sentences and spelled words, both hands,
repeated to 60 s (no two-hand capture ships). Prints figures, asserts nothing:

    .venv/bin/python bench/bench_hands.py
"""

import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))
sys.path.insert(0, str(Path(__file__).resolve().parent))

import machine
from machine import timed_ms

from synthesis.fingerspelling.spelling import spell
from synthesis.hands import (
    apply_reduction,
    find_reduction,
    marker_error_cm,
    rank_markers,
    reconstruct_hand,
    reconstruction_error_deg,
    virtual_markers,
)
from synthesis.hands.handover import builtin_pose_database
from synthesis.hands.motion import from_dofs
from synthesis.rigs.hand import HandModel
from synthesis.signing.sentence import SentenceOptions, synthesize
from synthesis.signing.stories import SPINE_STORY


def two_hands_60_s():
    """Return 60 s of the engine's two-handed signing at 30 fps, as a hand motion."""
    parts = [synthesize(text, SentenceOptions(rate_hz=30.0)) for text in SPINE_STORY]
    body = parts[0].body
    dofs = np.vstack([p.dofs_rad for p in parts])
    dofs = np.vstack([dofs] * int(np.ceil(1800 / len(dofs))))[:1800]
    return from_dofs(body, dofs, 30.0)


def main() -> int:
    print(machine.describe())
    motion = two_hands_60_s()
    curves = motion.curves_deg()
    for range_deg, rmsd in ((1.0, 0.3), (5.0, 0.5)):
        ms, reduction = timed_ms(
            lambda r=range_deg, m=rmsd: find_reduction(curves, motion.names, r, m)
        )
        errors = reconstruction_error_deg(curves, apply_reduction(curves, reduction))
        print(
            f"reduction, 60 s two hands at 30 fps ({len(motion.names)} curves), range < "
            f"{range_deg:g}° + rmsd < {rmsd:g}: {ms:.0f} ms; {reduction.dof_count} DOFs free, "
            f"mean error {errors.mean():.2f}° (engine motion)"
        )
    database = builtin_pose_database("right")
    ms, _ = timed_ms(lambda: rank_markers(database.markers))
    print(f"PCA marker ranking, {len(database.markers)} poses × 13 markers: {ms:.0f} ms")
    hand = HandModel("right")
    word = spell("PSYCHIATRY", "right", 120.0)
    truth = virtual_markers(hand, word)
    for method in ("lwr", "nearest"):
        for markers in (3, 6):
            reconstruct_hand(word[:10], "right", 120.0, markers, method)  # models built once
            ms, rebuilt = timed_ms(
                lambda m=markers, k=method: reconstruct_hand(word, "right", 120.0, m, k)
            )
            error, spread = marker_error_cm(truth, virtual_markers(hand, rebuilt))
            print(
                f"reconstruction ({method}, {markers} markers), PSYCHIATRY at 120 Hz, "
                f"{len(word)} frames: {len(word) / ms * 1000:,.0f} frames/s; marker error "
                f"{error:.2f} cm (s.d. {spread:.2f}); database: {database.source}"
            )
    paper_configuration(hand)
    return 0


def paper_configuration(hand) -> None:
    """Time seed 000 §3.1's configuration: Alg. 1 search and the whole Table 3.1."""
    import time

    from synthesis.hands.evaluation import paper_table_3_1
    from synthesis.hands.heldout import simulated_gestures
    from synthesis.hands.markers import search_marker_sets

    started = time.perf_counter()
    held_out = simulated_gestures("right", np.random.default_rng(0))
    built_s = time.perf_counter() - started
    clustered = held_out.database.clustered(1000, np.random.default_rng(0))
    choosing = virtual_markers(hand, held_out.selection_dofs[::4], "forearm")
    ms, _ = timed_ms(lambda: search_marker_sets(6, clustered.markers, choosing), repeat=1)
    print(
        f"Alg. 1 exhaustive search, m = 6 (1,716 sets), p = 1000, {len(choosing)} selection "
        f"frames: {ms:.0f} ms (simulated gestures)"
    )
    started = time.perf_counter()
    rows = paper_table_3_1(held_out, hand, 120.0, np.random.default_rng(0))
    print(
        f"Table 3.1 in the paper's configuration (simulated gestures, {len(rows)} cells): "
        f"{time.perf_counter() - started:.1f} s, after {built_s:.1f} s building "
        f"{len(held_out.database.dofs_rad):,} database poses"
    )


if __name__ == "__main__":
    sys.exit(main())
