"""Check that the mixed models' 95 % CIs cover the true effects (issue 21: ≥ 90 % of 200 runs).

Each run simulates a study with known condition effects and crossed random effects
(40 participants × 8 items; pairwise: every unordered pair of 4 conditions per item;
ratings: 3 conditions per item on a 1–5 scale), fits the model the report fits, and
counts whether each effect's Wald 95 % CI holds the truth. Prints coverage per effect;
asserts nothing. Simulated data.

    .venv/bin/python bench/bench_mixed_coverage.py [runs]
"""

import sys
import time
from concurrent.futures import ProcessPoolExecutor
from itertools import combinations
from pathlib import Path

import numpy as np
from threadpoolctl import threadpool_limits

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from analysis.mixed import fit_laplace, ordinal_problem, pairwise_problem
from analysis.power import Effects, PlannedDesign, Trial, simulate
from bench.machine import describe

PARTICIPANTS = 40
PAIRWISE = Effects(
    {"a": 0.0, "b": 0.5, "c": 0.2, "d": 0.8}, sd_participant=0.6, sd_item=0.4, position=0.2
)
RATING = Effects(
    {"a": 0.0, "b": 0.6, "c": -0.4},
    sd_participant=1.0,
    sd_item=0.5,
    thresholds=(-2.0, -0.6, 0.6, 2.0),
)


def designs() -> tuple[PlannedDesign, PlannedDesign]:
    items = [f"I{i}" for i in range(8)]
    pairs = tuple(
        tuple(
            Trial(item, *((a, b) if (i + k) % 2 else (b, a)))
            for i, item in enumerate(items)
            for a, b in combinations("abcd", 2)
        )
        for k in range(2)
    )
    rated = (tuple(Trial(item, c) for item in items for c in "abc"),)
    return PlannedDesign("pairwise", tuple("abcd"), pairs), PlannedDesign(
        "rating", tuple("abc"), rated
    )


def one_blas_thread() -> None:
    threadpool_limits(limits=1)


def one_run(seed: int) -> dict[str, bool]:
    rng = np.random.default_rng(seed)
    pair_design, rating_design = designs()
    covered = {}
    data = simulate(pair_design, PAIRWISE, PARTICIPANTS, rng)
    fit = fit_laplace(pairwise_problem(data, list("abcd")))
    truth = [PAIRWISE.position] + [PAIRWISE.effects[c] for c in "bcd"]
    for name, estimate, se, true in zip(
        fit.names, fit.params, np.sqrt(np.diag(fit.cov)), truth, strict=False
    ):
        covered[f"pairwise {name}"] = bool(abs(estimate - true) <= 1.959964 * se)
    data = simulate(rating_design, RATING, PARTICIPANTS, rng)
    fit = fit_laplace(ordinal_problem(data, list("abc")))
    for k, c in enumerate("bc"):
        se = np.sqrt(fit.cov[k, k])
        covered[f"ordinal {c}"] = bool(abs(fit.params[k] - RATING.effects[c]) <= 1.959964 * se)
    return covered


def main() -> None:
    runs = int(sys.argv[1]) if len(sys.argv) > 1 else 200
    print(describe())
    started = time.perf_counter()
    with ProcessPoolExecutor(initializer=one_blas_thread) as pool:
        results = list(pool.map(one_run, range(1000, 1000 + runs), chunksize=4))
    print(
        f"{runs} simulated studies in {time.perf_counter() - started:.0f} s "
        f"({PARTICIPANTS} participants × 8 items; SIMULATED data)"
    )
    for name in results[0]:
        share = np.mean([r[name] for r in results])
        print(f"  {name:<28} 95 % CI coverage {100 * share:5.1f} % (target ≥ 90 %)")


if __name__ == "__main__":
    main()
