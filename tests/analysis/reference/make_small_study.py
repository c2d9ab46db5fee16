"""Write small_study.csv, the golden report test's data (tests/analysis/test_golden_report.py).

Six participants, three labelled conditions, three items and one practice item:
every pair of conditions judged per item (both orders across participants), a 1–5
clarity rating and a typed answer per item × condition. Answers are whole words (no
misspellings), so accuracy is the share of target words typed, which the R script
small_study.R recomputes on its own. Regenerate with:

    .venv/bin/python tests/analysis/reference/make_small_study.py
    Rscript tests/analysis/reference/small_study.R
"""

from itertools import combinations
from pathlib import Path

import numpy as np
import pandas as pd

SEED = 20261203
CONDITIONS = {"ctl": "Constant timing", "bayes": "Bayesian timing", "mocap": "Motion capture"}
STRENGTH = {"ctl": -0.6, "bayes": 0.3, "mocap": 0.5}
ITEMS = {"GUITAR": "GUITAR", "TOY-CAR": "TOY CAR", "MY-HOUSE": "MY HOUSE RED"}
PRACTICE = "HELLO"


def _row(participant, trial, item, kind, a, b="", **cells) -> dict:
    return {
        "participant": participant,
        "study": "small",
        "block": kind,
        "trial": trial,
        "item": item,
        "kind": kind,
        "condition_a": a,
        "condition_b": b,
        "condition_a_label": CONDITIONS.get(a, ""),
        "condition_b_label": CONDITIONS.get(b, ""),
        "chosen": "",
        "question": "",
        "rating": "",
        "text": "",
        "rt_ms": "",
        "flags": "",
        "target": "",
        **cells,
    }


def _answer(rng, target: str, clarity: float) -> str:
    words = target.split()
    kept = [w for w in words if rng.random() < clarity]
    return " ".join(kept) if kept else "not sure"


def generate(rng: np.random.Generator) -> pd.DataFrame:
    rows = []
    for p in range(1, 7):
        who = f"P{p}"
        own = rng.normal(0, 0.4, size=len(CONDITIONS))
        rows.append(
            _row(
                who,
                "practice",
                PRACTICE,
                "pairwise",
                "ctl",
                "bayes",
                chosen="bayes",
                flags="practice",
            )
        )
        for item in ITEMS:
            for k, (a, b) in enumerate(combinations(CONDITIONS, 2)):
                first, second = (a, b) if (p + k) % 2 else (b, a)
                edge = STRENGTH[first] - STRENGTH[second] + own[k] - own[(k + 1) % 3]
                roll = rng.random()
                wins = roll < 1 / (1 + np.exp(-edge))
                chosen = "none" if roll < 0.1 else first if wins else second
                rows.append(
                    _row(
                        who,
                        f"{item}-{first}-{second}",
                        item,
                        "pairwise",
                        first,
                        second,
                        chosen=chosen,
                        question="most-natural",
                        rt_ms=str(int(rng.integers(1500, 6000))),
                    )
                )
            for c, condition in enumerate(CONDITIONS):
                rating = int(
                    np.clip(
                        np.rint(3 + 1.5 * STRENGTH[condition] + own[c] + rng.normal(0, 0.8)), 1, 5
                    )
                )
                rows.append(
                    _row(
                        who,
                        f"rate-{item}-{condition}",
                        item,
                        "rating",
                        condition,
                        question="clarity",
                        rating=str(rating),
                    )
                )
                clarity = 0.55 + 0.3 * STRENGTH[condition] + 0.1 * own[c]
                rows.append(
                    _row(
                        who,
                        f"type-{item}-{condition}",
                        item,
                        "text",
                        condition,
                        question="what-signed",
                        target=ITEMS[item],
                        text=_answer(rng, ITEMS[item], clarity),
                    )
                )
    return pd.DataFrame(rows)


if __name__ == "__main__":
    out = Path(__file__).with_name("small_study.csv")
    generate(np.random.default_rng(SEED)).to_csv(out, index=False)
    print(f"wrote {out}")
