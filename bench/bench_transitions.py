"""Measure issue 17's targets: database build, one search + fit, a 10-sign sentence.

Targets: one search + fit under 5 ms; a 10-sign sentence with data-driven transitions
assembled in under 100 ms without rendering. The database build (100 transitions) has
no target. The data are simulated captures (labelled simulated). Prints figures,
asserts nothing:

    .venv/bin/python bench/bench_transitions.py
"""

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))
sys.path.insert(0, str(Path(__file__).resolve().parent))

import machine
from machine import timed_ms

from synthesis.signing.sentence import SentenceOptions, synthesize
from synthesis.transitions import (
    DescriptorSearch,
    build_database,
    cut_transitions,
    simulated_captures,
    transition,
)
from synthesis.transitions.database import entry_from_cut
from synthesis.transitions.sentence import retransition

TEN_SIGNS = "BUT SURPRISE MY BROTHER GET NEW BLUE COLOR FINALLY HAPPY"


def main() -> int:
    print(machine.describe())
    recordings = simulated_captures(signers=4, sentences=6, seed=0)
    cuts = [cut for recording in recordings for cut in cut_transitions(recording, 5.0)][:100]
    build_ms, _entries = timed_ms(lambda: [entry_from_cut(c) for c in cuts], repeat=3)
    print(
        f"database build, {len(cuts)} transitions (7 curves, Hermite + B-spline fits, "
        f"descriptor): {build_ms:,.0f} ms ({build_ms / len(cuts):.1f} ms a transition)"
    )
    database = build_database(recordings)
    search = DescriptorSearch(database, "raw")
    entry = database.entries[len(database.entries) // 2]
    for model in ("hermite", "bspline"):
        ms, _ = timed_ms(
            lambda m=model: transition(
                m, entry.before, entry.after, entry.gap_frames, search, {entry.id}
            ),
            repeat=50,
        )
        print(
            f"one search + fit ({model}, {len(database.entries)} entries, "
            f"{entry.gap_frames} frames): {ms:.2f} ms (target < 5 ms)"
        )
    options = SentenceOptions(rate_hz=60.0)
    sentence = synthesize(TEN_SIGNS, options)
    keyed_ms, _ = timed_ms(lambda: synthesize(TEN_SIGNS, options))
    for model in ("hermite", "bspline", "simple_hermite"):
        ms, _ = timed_ms(lambda m=model: retransition(sentence, m, search), repeat=10)
        print(
            f"10-sign sentence, 9 gaps, {model} transitions: {keyed_ms + ms:.1f} ms in all "
            f"(target < 100 ms): synthesis {keyed_ms:.1f} ms + transitions {ms:.1f} ms"
        )
    return 0


if __name__ == "__main__":
    sys.exit(main())
