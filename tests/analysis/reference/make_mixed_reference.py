"""Write data sets with known effects and R's fits of them for test_mixed_reference.py.

The data are generated here with numpy (seeded); R 4.2 with lme4 1.1-31 and ordinal
2022.11-16 (Debian bookworm's r-cran-lme4 and r-cran-ordinal, not project
dependencies) fits them in mixed_reference.R. Regenerate with:

    apt-get install r-cran-lme4 r-cran-ordinal
    .venv/bin/python tests/analysis/reference/make_mixed_reference.py
"""

import subprocess
from itertools import combinations
from pathlib import Path

import numpy as np
import pandas as pd
from scipy.special import expit

FOLDER = Path(__file__).parent
SEED = 20261202
CONDITIONS = ("a", "b", "c", "d")
STRENGTHS = {"a": 0.0, "b": 0.8, "c": 0.4, "d": 1.1}
POSITION = 0.25
THRESHOLDS = np.array([-2.0, -0.6, 0.6, 2.0])


def pairwise(rng: np.random.Generator, participants: int = 48, items: int = 8) -> pd.DataFrame:
    """Forced choices: every participant judges every unordered pair of every item once.

    logit P(clip 1 chosen) = position + s[clip1] − s[clip2] + u_p + w_p·(x_b) + u_i,
    with SDs 0.7 (participant position bias), 0.6 (participant's own strength of b)
    and 0.4 (item).
    """
    u_participant = rng.normal(0, 0.7, participants)
    slope_b = rng.normal(0, 0.6, participants)
    u_item = rng.normal(0, 0.4, items)
    rows = []
    for p in range(participants):
        for i in range(items):
            for a, b in combinations(CONDITIONS, 2):
                clip1, clip2 = (a, b) if rng.random() < 0.5 else (b, a)
                x = {c: float(c == clip1) - float(c == clip2) for c in CONDITIONS}
                eta = (
                    POSITION
                    + STRENGTHS[clip1]
                    - STRENGTHS[clip2]
                    + u_participant[p]
                    + slope_b[p] * x["b"]
                    + u_item[i]
                )
                rows.append(
                    {
                        "participant": f"P{p + 1:02d}",
                        "item": f"W{i + 1}",
                        "clip1": clip1,
                        "clip2": clip2,
                        "first": int(rng.random() < expit(eta)),
                        "x_b": x["b"],
                        "x_c": x["c"],
                        "x_d": x["d"],
                    }
                )
    return pd.DataFrame(rows)


def ratings(
    rng: np.random.Generator, participants: int = 36, items: int = 10, slopes=None
) -> pd.DataFrame:
    """Likert 1–5: P(Y ≤ k) = logit⁻¹(θ_k − β[condition] − u_p − u_i), SDs 1.0 and 0.5.

    Every participant rates every item in every condition. With *slopes* (one row of
    threshold shifts per condition) the odds are not proportional.
    """
    effect = {"a": 0.0, "b": 0.7, "c": -0.5}
    u_participant = rng.normal(0, 1.0, participants)
    u_item = rng.normal(0, 0.5, items)
    rows = []
    for p in range(participants):
        for i in range(items):
            for index, condition in enumerate(effect):
                eta = effect[condition] + u_participant[p] + u_item[i]
                thresholds = THRESHOLDS if slopes is None else THRESHOLDS + slopes[index]
                cumulative = expit(np.sort(thresholds) - eta)
                rating = 1 + int((rng.random() > cumulative).sum())
                rows.append(
                    {
                        "participant": f"P{p + 1:02d}",
                        "item": f"S{i + 1}",
                        "condition": condition,
                        "rating": rating,
                    }
                )
    return pd.DataFrame(rows)


def main() -> None:
    rng = np.random.default_rng(SEED)
    pairwise(rng).to_csv(FOLDER / "mixed_pairwise.csv", index=False)
    ratings(rng).to_csv(FOLDER / "mixed_ratings.csv", index=False)
    spread = np.array([[0, 0, 0, 0], [-1.2, -0.4, 0.4, 1.2], [0, 0, 0, 0]])
    ratings(rng, participants=40, items=5, slopes=spread).to_csv(
        FOLDER / "mixed_nonproportional.csv", index=False
    )
    subprocess.run(["Rscript", str(FOLDER / "mixed_reference.R"), str(FOLDER)], check=True)
    print(f"Wrote {FOLDER / 'mixed_reference.json'}")


if __name__ == "__main__":
    main()
