"""Measure issue 17's targets: database build, one search + fit, a 10-sign sentence.

Targets: one search + fit under 5 ms; a 10-sign sentence with data-driven transitions
assembled in under 100 ms without rendering. The database build (100 transitions) has
no target. Issue 38: App. A.1.2's 100 tangent lengths against the 24 used before, and
the coarse-to-fine search against trying all 100 × 100 pairs. The data are simulated
captures (labelled simulated). Prints figures, asserts nothing:

    .venv/bin/python bench/bench_transitions.py
"""

import sys
import time
from pathlib import Path

import numpy as np

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
from synthesis.transitions.hermite_fit import COARSE_STRIDE, fit_segment, smooth, splice_points
from synthesis.transitions.sentence import retransition

TEN_SIGNS = "BUT SURPRISE MY BROTHER GET NEW BLUE COLOR FINALLY HAPPY"


def _segments(cuts) -> list[tuple]:
    """Return the Hermite segments the database fits for *cuts* (as fit_hermite cuts them)."""
    found = []
    for cut in cuts:
        span = np.vstack([cut.before[-1:], cut.gap, cut.after[:1]])
        for values in span.T:
            delta = float(np.ptp(values))
            y = (values - values.min()) / delta if delta > 1e-12 else np.zeros_like(values)
            smoothed = smooth(y)
            frames = splice_points(smoothed, max(3, len(y) // 8))
            directions = np.column_stack([np.ones(len(frames)), np.gradient(smoothed)[frames]])
            directions /= np.linalg.norm(directions, axis=1)[:, None]
            for a, b, d0, d1 in zip(
                frames[:-1], frames[1:], directions[:-1], directions[1:], strict=True
            ):
                found.append((np.arange(a, b + 1, dtype=float), y[a : b + 1], d0, d1, delta))
    return found


def tangent_search(cuts) -> None:
    """Print App. A.1.2's tangent-length search: 24 against 100 lengths, exhaustive
    against coarse to fine (fit error in degrees, time a segment)."""
    segments = _segments(cuts)
    errors = {}
    searches = (
        ("24 lengths, all pairs", 24, 1),
        ("100 lengths, all pairs", 100, 1),
        ("100 lengths, coarse to fine (default)", 100, COARSE_STRIDE),
    )
    for name, steps, coarse in searches:
        started = time.perf_counter()
        errors[name] = np.array(
            [
                fit_segment(x, y, d0, d1, steps, coarse)[2] * np.degrees(delta)
                for x, y, d0, d1, delta in segments
            ]
        )
        ms = 1000 * (time.perf_counter() - started) / len(segments)
        print(
            f"Hermite segment fit, {name}: mean RMSE {errors[name].mean():.4f} deg over "
            f"{len(segments)} segments, {ms:.2f} ms a segment"
        )
    full, fast = errors["100 lengths, all pairs"], errors["100 lengths, coarse to fine (default)"]
    same = np.isclose(full, fast, rtol=1e-9, atol=1e-12).mean()
    print(
        f"coarse to fine finds the all-pairs optimum in {100 * same:.1f} % of segments; "
        f"worst excess {np.max(fast - full):.2g} deg"
    )


def main() -> int:
    print(machine.describe())
    recordings = simulated_captures(signers=4, sentences=6, seed=0)
    cuts = [cut for recording in recordings for cut in cut_transitions(recording, 5.0)][:100]
    build_ms, _entries = timed_ms(lambda: [entry_from_cut(c) for c in cuts], repeat=3)
    print(
        f"database build, {len(cuts)} transitions (7 curves, Hermite + B-spline fits, "
        f"descriptor): {build_ms:,.0f} ms ({build_ms / len(cuts):.1f} ms a transition)"
    )
    tangent_search(cuts[:40])
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
