"""Time a full analysis report for 1,000 participants × 48 pairwise trials.

Target (issue 8): < 5 s excluding figure rendering. Prints the time of each stage and
the figures' time separately; asserts nothing.

    .venv/bin/python bench/bench_report.py
"""

import sys
import tempfile
import time
from itertools import combinations
from pathlib import Path

import numpy as np
import pandas as pd

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from analysis import build_report, check_responses, read_responses, write_report
from analysis.exclusions import apply_exclusions
from analysis.tidy import REQUIRED_COLUMNS

PARTICIPANTS = 1000
CONDITIONS = ["constant", "mocap", "normalized", "variable"]
WORDS = ["GUITAR", "HEAVEN", "ARREST", "ELEPHANT", "PSYCHIATRY", "DAVID", "MICHAEL", "VICTOR"]
STRENGTH = {"constant": -0.6, "mocap": 0.2, "normalized": 0.0, "variable": 0.3}


def simulate(rng: np.random.Generator) -> pd.DataFrame:
    """Return 1,000 × 48 Bradley–Terry-distributed judgements in the tidy format."""
    pages = [
        (word, a, b) if (i + j) % 2 == 0 else (word, b, a)
        for i, word in enumerate(WORDS)
        for j, (a, b) in enumerate(combinations(CONDITIONS, 2))
    ]
    n = PARTICIPANTS * len(pages)
    participant = np.repeat([f"P{p:04d}" for p in range(PARTICIPANTS)], len(pages))
    word, clip1, clip2 = (
        np.tile(np.array(column), PARTICIPANTS) for column in zip(*pages, strict=True)
    )
    logit = np.vectorize(STRENGTH.get)(clip1) - np.vectorize(STRENGTH.get)(clip2)
    first_wins = rng.random(n) < 1 / (1 + np.exp(-logit))
    frame = pd.DataFrame({column: [""] * n for column in REQUIRED_COLUMNS})
    frame["participant"] = participant
    frame["study"] = "bench"
    frame["block"] = "comparisons"
    frame["trial"] = np.tile([f"cmp-{k:02d}" for k in range(len(pages))], PARTICIPANTS)
    frame["item"] = word
    frame["kind"] = "pairwise"
    frame["condition_a"] = clip1
    frame["condition_b"] = clip2
    frame["chosen"] = np.where(first_wins, clip1, clip2)
    frame["question"] = "most-natural"
    frame["rt_ms"] = rng.integers(800, 6000, n).astype(str)
    return frame


def main() -> None:
    frame = simulate(np.random.default_rng(8))
    with tempfile.TemporaryDirectory() as folder:
        csv = Path(folder) / "responses.csv"
        frame.to_csv(csv, index=False)
        size_mb = csv.stat().st_size / 1e6

        started = time.perf_counter()
        table = read_responses(csv)
        read_s = time.perf_counter() - started

        started = time.perf_counter()
        report = build_report(table)
        analyse_s = time.perf_counter() - started

        kept, _ = apply_exclusions(table)
        started = time.perf_counter()
        write_report(report, kept, Path(folder) / "out", draw_figures=False)
        write_s = time.perf_counter() - started

        started = time.perf_counter()
        write_report(report, kept, Path(folder) / "figs", draw_figures=True)
        with_figures_s = time.perf_counter() - started

    check_s = time.perf_counter()
    check_responses(frame)
    check_s = time.perf_counter() - check_s
    total = read_s + analyse_s + write_s
    print(f"rows: {len(frame):,} ({PARTICIPANTS} participants × 48 trials), CSV {size_mb:.1f} MB")
    print(f"read + check CSV: {read_s * 1000:.0f} ms (check alone {check_s * 1000:.0f} ms)")
    print(f"analyses: {analyse_s * 1000:.0f} ms")
    print(f"write JSON, tables, HTML: {write_s * 1000:.0f} ms")
    print(f"full report without figures: {total:.2f} s (target < 5 s)")
    print(
        f"writing with figures: {with_figures_s:.2f} s (figures ≈ {with_figures_s - write_s:.2f} s)"
    )


if __name__ == "__main__":
    main()
