"""Time a 10-point power curve of 200 simulations each (issue 21; target < 2 min), and
check the simulation against closed forms (within 5 points at the closed-form N).

Curve: the pairwise design of the fingerspelling study (4 conditions × 8 words, every
unordered pair per word, positions counterbalanced over two lists), N = 10 … 55, with
the mixed model and the binomial tests. Check: two conditions, 4 trials per participant,
P(b chosen) = 0.65, no random effects; the exact binomial test needs n trials (closed
form); at N = n / 4 the simulated power of the binomial test and of the mixed model's
Wald test are compared with the closed-form power. Simulated data; asserts nothing.

    .venv/bin/python bench/bench_power.py
"""

import sys
import time
from itertools import combinations
from pathlib import Path

from scipy.special import logit

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from analysis.power import (
    Effects,
    PlannedDesign,
    Trial,
    binomial_n,
    binomial_power,
    power_curve,
)
from bench.machine import describe


def main() -> None:
    print(describe())
    words = [f"W{i}" for i in range(8)]
    conditions = ("constant", "mocap", "normalized", "variable")
    lists = tuple(
        tuple(
            Trial(w, *((a, b) if (i + k) % 2 else (b, a)))
            for i, w in enumerate(words)
            for a, b in combinations(conditions, 2)
        )
        for k in range(2)
    )
    design = PlannedDesign("pairwise", conditions, lists)
    effects = Effects(
        {"constant": 0.0, "mocap": 0.25, "normalized": 0.15, "variable": 0.3},
        sd_participant=0.5,
        sd_item=0.3,
    )
    started = time.perf_counter()
    curve = power_curve(design, effects, range(10, 56, 5), simulations=200, seed=1)
    print(
        f"10-point curve × 200 simulations: {time.perf_counter() - started:.1f} s (target < 120 s)"
    )
    print(curve.summary())

    p, trials = 0.65, 4
    n_trials = binomial_n(p)
    participants = -(-n_trials // trials)
    expected = binomial_power(participants * trials, p)
    pair = ((Trial("W", "a", "b"), Trial("W", "b", "a")) * (trials // 2),)
    check = power_curve(
        PlannedDesign("pairwise", ("a", "b"), pair),
        Effects({"a": 0.0, "b": float(logit(p))}),
        [participants],
        simulations=1000,
        seed=2,
    )
    print(
        f"Closed form: exact binomial test, P = {p}, needs {n_trials} trials for 80 % power; "
        f"N = {participants} participants × {trials} trials gives {100 * expected:.1f} %."
    )
    for test in ("binomial: b vs a", "mixed: b vs a"):
        simulated = check.power(test, participants)
        print(
            f"  simulated {test}: {100 * simulated:.1f} % (1000 studies), "
            f"difference {100 * (simulated - expected):+.1f} points (target within 5)"
        )


if __name__ == "__main__":
    main()
