"""Time the mixed models on 1,000 participants × 48 trials (issues 21, 34; target < 30 s each).

Pairwise: 4 conditions, 8 words, every unordered pair of every word once (48 trials),
fitted with participant and item intercepts (the report's default), and with
participants' own strengths (opt-in: 4 more random-effect columns per participant).
Ratings: 3 conditions × 16 sentences rated 1–5 (48 trials), the cumulative-link and the
linear mixed model (REML and ML, and with participants' own condition effects). Data
are simulated. Prints each fit's time and its estimates next to the truth; asserts
nothing.

    .venv/bin/python bench/bench_mixed.py
"""

import sys
import time
from itertools import combinations
from pathlib import Path

import numpy as np
import pandas as pd
from scipy.special import expit

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from analysis import check_responses
from analysis.mixed import linear_mixed, mixed_bradley_terry, ordinal_mixed
from bench.machine import describe

PARTICIPANTS = 1000
STRENGTH = {"constant": 0.0, "mocap": 0.8, "normalized": 0.6, "variable": 0.9}
RATING_EFFECT = {"off": 0.0, "on": 0.5, "spine": 0.3}
THRESHOLDS = np.array([-2.0, -0.7, 0.6, 2.0])


def _frame(columns: dict) -> pd.DataFrame:
    n = len(columns["participant"])
    base = {"study": "bench", "block": "b", "trial": [f"t{i}" for i in range(n)]}
    base |= {"condition_b": "", "chosen": "", "question": "", "rating": "", "text": ""}
    base |= {"rt_ms": "", "flags": ""}
    return check_responses(pd.DataFrame({**base, **columns}).astype(str))


def pairwise(rng: np.random.Generator) -> pd.DataFrame:
    words = [f"W{i}" for i in range(8)]
    bias, item = rng.normal(0, 0.5, PARTICIPANTS), rng.normal(0, 0.3, len(words))
    rows = []
    for p in range(PARTICIPANTS):
        for w, word in enumerate(words):
            for a, b in combinations(STRENGTH, 2):
                a, b = (a, b) if rng.random() < 0.5 else (b, a)
                eta = 0.1 + STRENGTH[a] - STRENGTH[b] + bias[p] + item[w]
                rows.append((f"P{p}", word, a, b, a if rng.random() < expit(eta) else b))
    p, w, a, b, chosen = zip(*rows, strict=True)
    return _frame(
        {
            "participant": p,
            "item": w,
            "kind": "pairwise",
            "condition_a": a,
            "condition_b": b,
            "chosen": chosen,
        }
    )


def ratings(rng: np.random.Generator) -> pd.DataFrame:
    sentences = [f"S{i}" for i in range(16)]
    person, item = rng.normal(0, 1.0, PARTICIPANTS), rng.normal(0, 0.4, len(sentences))
    rows = []
    for p in range(PARTICIPANTS):
        for s, sentence in enumerate(sentences):
            for condition, effect in RATING_EFFECT.items():
                eta = effect + person[p] + item[s]
                rating = 1 + int((rng.random() > expit(THRESHOLDS - eta)).sum())
                rows.append((f"P{p}", sentence, condition, rating))
    p, s, c, r = zip(*rows, strict=True)
    return _frame(
        {
            "participant": p,
            "item": s,
            "kind": "rating",
            "condition_a": c,
            "question": "natural",
            "rating": r,
        }
    )


def timed(label: str, function, *args, **kwargs):
    started = time.perf_counter()
    result = function(*args, **kwargs)
    print(
        f"{label}: {time.perf_counter() - started:.1f} s (target < 30 s), "
        f"{result.nobs} observations, converged: {result.converged}"
    )
    return result


def main() -> None:
    print(describe())
    rng = np.random.default_rng(21)
    choices, rated = pairwise(rng), ratings(rng)
    bt = timed(
        "Mixed Bradley–Terry, participant and item intercepts",
        mixed_bradley_terry,
        choices,
        list(STRENGTH),
    )
    print(
        "  strengths",
        {e.name: round(e.estimate, 3) for e in bt.effects},
        "truth",
        STRENGTH,
        "; SDs",
        {c.name: round(c.sd, 3) for c in bt.random},
        "truth participant 0.5, item 0.3",
    )
    bt_own = timed(
        "Mixed Bradley–Terry + participants' own strengths",
        mixed_bradley_terry,
        choices,
        list(STRENGTH),
        random_strengths=True,
    )
    print("  SDs", {c.name: round(c.sd, 3) for c in bt_own.random}, "truth strengths 0")
    clmm = timed(
        "Cumulative-link mixed model", ordinal_mixed, rated, "natural", list(RATING_EFFECT)
    )
    print(
        "  effects",
        {e.name: round(e.estimate, 3) for e in clmm.effects},
        "truth",
        RATING_EFFECT,
        "; SDs",
        {c.name: round(c.sd, 3) for c in clmm.random},
        "truth 1.0, 0.4",
    )
    lmm = timed(
        "Linear mixed model (REML, Satterthwaite df, LR test, profile CIs of the SDs)",
        linear_mixed,
        rated,
        "natural",
        list(RATING_EFFECT),
    )
    print("  effects", {e.name: round(e.estimate, 3) for e in lmm.effects})
    print("  SDs", {c.name: (round(c.sd, 3), tuple(round(v, 3) for v in c.ci)) for c in lmm.random})
    ml = timed(
        "Linear mixed model (ML)", linear_mixed, rated, "natural", list(RATING_EFFECT), reml=False
    )
    print("  effects", {e.name: round(e.estimate, 3) for e in ml.effects})
    slopes = timed(
        "Linear mixed model + (condition | participant), REML",
        linear_mixed,
        rated,
        "natural",
        list(RATING_EFFECT),
        slopes=True,
    )
    print(
        "  SDs",
        {f"{c.name} {c.column}": round(c.sd, 3) for c in slopes.random},
        "truth participant 1.0 (on the latent scale), no slopes; singular:",
        slopes.singular,
    )


if __name__ == "__main__":
    main()
