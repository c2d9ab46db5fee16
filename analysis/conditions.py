"""Summarise and compare conditions across items on participants' means.

A rating question or the intelligibility accuracy is first averaged per participant and
condition over the items they saw, so each participant counts once; the conditions are
then described (mean, SD, SEM and t-based 95 % CI over participants; median and
quartiles over the answers) and every two conditions compared by a paired t-test and a
Wilcoxon signed-rank test on the participants who saw both, corrected across the pairs
of one measure (spec 07 "Ratings", "Intelligibility").
"""

import dataclasses
from itertools import combinations

import numpy as np
import pandas as pd
from scipy import stats

from analysis.summaries import ConditionComparison, ConditionSummary
from analysis.within import adjust, paired_ttest, wilcoxon_test

# The columns of a long table of scores: one row per answer.
SCORE_COLUMNS = ("measure", "participant", "item", "condition", "score")


def _ci(values: np.ndarray) -> tuple[float, float]:
    n = values.size
    if n < 2:
        return (float("nan"), float("nan"))
    mean, sem = values.mean(), values.std(ddof=1) / np.sqrt(n)
    half = stats.t.ppf(0.975, n - 1) * sem
    return (float(mean - half), float(mean + half))


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
        ci=_ci(means),
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
    found = []
    for measure, rows in scores.groupby("measure", sort=True):
        wide = rows.pivot_table(
            index="participant", columns="condition", values="score", aggfunc="mean"
        )
        tests = []
        for a, b in combinations(sorted(wide.columns), 2):
            paired = wide[[a, b]].dropna()
            if len(paired) < 2:
                continue
            x, y = paired[a].to_numpy(), paired[b].to_numpy()
            tests.append(
                (a, b, len(paired), wilcoxon_test(x, y, (a, b)), paired_ttest(x, y, (a, b)))
            )
        wilcoxon_adjusted = adjust([t[3].pvalue for t in tests], correction)
        ttest_adjusted = adjust([t[4].pvalue for t in tests], correction)
        for (a, b, n, w, t), pw, pt in zip(tests, wilcoxon_adjusted, ttest_adjusted, strict=True):
            found.append(
                ConditionComparison(
                    measure=measure,
                    a=a,
                    b=b,
                    nobs=n,
                    wilcoxon=dataclasses.replace(w, pvalue_adjusted=float(pw)),
                    ttest=dataclasses.replace(t, pvalue_adjusted=float(pt)),
                )
            )
    return tuple(found)
