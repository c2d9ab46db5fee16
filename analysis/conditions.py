"""Summarise and compare conditions across items on participants' means.

A rating question or the intelligibility accuracy is first averaged per participant and
condition over the items they saw, so each participant counts once; the conditions are
then described (mean, SD, SEM and t-based 95 % CI over participants; median and
quartiles over the answers) and every two conditions compared by a paired t-test and a
Wilcoxon signed-rank test on the participants who saw both, corrected across the pairs
of one measure (spec 07 "Ratings", "Intelligibility").
"""

import numpy as np
import pandas as pd

from analysis.summaries import ConditionComparison, ConditionSummary
from analysis.within import adjust_comparisons, mean_ci, paired_comparisons

# The columns of a long table of scores: one row per answer.
SCORE_COLUMNS = ("measure", "participant", "item", "condition", "score")


def _summary(measure: str, condition: str, answers: pd.DataFrame) -> ConditionSummary:
    means = answers.groupby("participant")["score"].mean().to_numpy()
    scores = answers["score"].to_numpy(float)
    n = means.size
    sd = float(means.std(ddof=1)) if n > 1 else float("nan")
    return ConditionSummary(
        measure=measure,
        condition=condition,
        n=int(scores.size),
        nobs=int(n),
        items=int(answers["item"].nunique()),
        mean=float(means.mean()),
        sd=sd,
        sem=sd / np.sqrt(n) if n > 1 else float("nan"),
        ci=mean_ci(means),
        median=float(np.median(scores)),
        q1=float(np.percentile(scores, 25)),
        q3=float(np.percentile(scores, 75)),
    )


def summarize_conditions(scores: pd.DataFrame) -> tuple[ConditionSummary, ...]:
    """Describe each measure × condition of a long score table (SCORE_COLUMNS)."""
    scores = scores.dropna(subset=["score"])
    return tuple(
        _summary(measure, condition, answers)
        for (measure, condition), answers in scores.groupby(["measure", "condition"], sort=True)
    )


def compare_conditions(
    scores: pd.DataFrame, correction: str = "holm"
) -> tuple[ConditionComparison, ...]:
    """Compare every two conditions of each measure on participants' means (paired)."""
    scores = scores.dropna(subset=["score"])
    found: list[ConditionComparison] = []
    for measure, rows in scores.groupby("measure", sort=True):
        wide = rows.pivot_table(
            index="participant", columns="condition", values="score", aggfunc="mean"
        )
        found += adjust_comparisons(
            paired_comparisons(wide, ConditionComparison, measure=measure), correction
        )
    return tuple(found)
