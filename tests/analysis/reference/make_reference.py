"""Write reference values for tests/analysis/test_reference.py with an independent library.

pingouin (not a project dependency) computes the repeated-measures ANOVA with Mauchly's
test and Greenhouse–Geisser correction, paired t-tests with Holm correction, the
Friedman test and Wilcoxon signed-rank tests on generated data; d_z is computed by hand
from its definition. Regenerate with:

    python3.11 -m venv /tmp/refenv
    /tmp/refenv/bin/pip install pingouin==0.7.0 numpy==2.4.6 scipy==1.17.1 \\
        pandas==3.1.1 statsmodels==0.15.0
    /tmp/refenv/bin/python tests/analysis/reference/make_reference.py
"""

import json
from itertools import combinations
from pathlib import Path

import numpy as np
import pandas as pd
import pingouin

SEED = 20261122
LEVELS = ["constant", "mocap", "normalized", "variable"]


def generate(rng: np.random.Generator, subjects: int) -> pd.DataFrame:
    """Scores with subject effects, level effects and unequal variances (non-spherical)."""
    subject_effect = rng.normal(0, 0.08, size=(subjects, 1))
    level_effect = np.array([-0.12, 0.05, 0.0, 0.08])
    noise = rng.normal(0, 1, size=(subjects, len(LEVELS))) * np.array([0.05, 0.15, 0.08, 0.2])
    scores = 0.5 + subject_effect + level_effect + noise
    return pd.DataFrame(scores, columns=LEVELS, index=[f"P{i + 1:02d}" for i in range(subjects)])


def reference(scores: pd.DataFrame) -> dict:
    long = (
        scores.rename_axis("subject")
        .reset_index()
        .melt(id_vars="subject", var_name="level", value_name="value")
    )
    aov = pingouin.rm_anova(
        data=long, dv="value", within="level", subject="subject", correction=True, effsize="np2"
    ).iloc[0]
    pairs = pingouin.pairwise_tests(
        data=long, dv="value", within="level", subject="subject", padjust="holm", parametric=True
    )
    posthoc = []
    for _, row in pairs.iterrows():
        difference = scores[row["A"]] - scores[row["B"]]
        posthoc.append(
            {
                "a": row["A"],
                "b": row["B"],
                "t": float(row["T"]),
                "df": float(row["dof"]),
                "p": float(row["p_unc"] if "p_unc" in row else row["p-unc"]),
                "p_holm": float(row["p_corr"] if "p_corr" in row else row["p-corr"]),
                "dz": float(difference.mean() / difference.std(ddof=1)),
            }
        )
    friedman = pingouin.friedman(data=long, dv="value", within="level", subject="subject").iloc[0]
    wilcoxon = []
    for a, b in combinations(LEVELS, 2):
        result = pingouin.wilcoxon(scores[a], scores[b]).iloc[0]
        wilcoxon.append(
            {
                "a": a,
                "b": b,
                "W": float(result["W_val"] if "W_val" in result else result["W-val"]),
                "p": float(result["p_val"] if "p_val" in result else result["p-val"]),
                "rank_biserial": float(result["RBC"]),
            }
        )

    def pick(row, *names):
        for name in names:
            if name in row:
                return float(row[name])
        raise KeyError(names)

    return {
        "rm_anova": {
            "F": pick(aov, "F"),
            "df_num": pick(aov, "ddof1"),
            "df_den": pick(aov, "ddof2"),
            "p": pick(aov, "p_unc", "p-unc"),
            "p_gg": pick(aov, "p_GG_corr", "p-GG-corr"),
            "epsilon_gg": pick(aov, "eps"),
            "eta_p2": pick(aov, "np2"),
            "mauchly_w": pick(aov, "W_spher", "W-spher"),
            "mauchly_p": pick(aov, "p_spher", "p-spher"),
        },
        "posthoc": posthoc,
        "friedman": {
            "Q": pick(friedman, "Q"),
            "df": pick(friedman, "ddof1"),
            "p": pick(friedman, "p_unc", "p-unc"),
            "W": pick(friedman, "W"),
        },
        "wilcoxon": wilcoxon,
    }


def main() -> None:
    rng = np.random.default_rng(SEED)
    datasets = []
    for subjects in (10, 24):
        scores = generate(rng, subjects)
        datasets.append(
            {
                "scores": {column: scores[column].tolist() for column in scores.columns},
                "subjects": scores.index.tolist(),
                "expected": reference(scores),
            }
        )
    out = Path(__file__).with_name("within_subject.json")
    payload = {
        "source": "pingouin " + pingouin.__version__ + " via make_reference.py",
        "seed": SEED,
        "datasets": datasets,
    }
    out.write_text(json.dumps(payload, indent=2) + "\n")
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
