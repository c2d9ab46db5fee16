"""Fit Bradley–Terry strengths to paired-comparison counts by logistic regression."""

from collections.abc import Sequence

import numpy as np
import pandas as pd
import statsmodels.api as sm

from analysis.results import BradleyTerryResult, Strength


def bradley_terry(counts: pd.DataFrame, conditions: Sequence[str]) -> BradleyTerryResult:
    """Return each condition's log-worth relative to ``conditions[0]`` (fixed at 0).

    *counts* has columns ``a, b, a_wins, b_wins``. Model: logit P(a beats b) = β_a − β_b
    (Bradley & Terry 1952), fitted as a binomial GLM without intercept; CIs are Wald 95 %.
    """
    conditions = list(conditions)
    reference, others = conditions[0], conditions[1:]
    counts = counts[(counts["a_wins"] + counts["b_wins"]) > 0]
    design = np.zeros((len(counts), len(others)))
    column = {condition: index for index, condition in enumerate(others)}
    for row, (a, b) in enumerate(zip(counts["a"], counts["b"], strict=True)):
        if a in column:
            design[row, column[a]] += 1.0
        if b in column:
            design[row, column[b]] -= 1.0
    outcome = counts[["a_wins", "b_wins"]].to_numpy(dtype=float)
    # With as many pairs as parameters the model is saturated (0 residual df); the IRLS
    # step then divides by zero for a scale the binomial family never uses.
    with np.errstate(divide="ignore", invalid="ignore"):
        fit = sm.GLM(outcome, design, family=sm.families.Binomial()).fit()
    intervals = np.asarray(fit.conf_int(0.05))
    strengths = [Strength(reference, 0.0, 0.0, (0.0, 0.0), 1.0)]
    for index, condition in enumerate(others):
        log_worth = float(fit.params[index])
        strengths.append(
            Strength(
                condition=condition,
                log_worth=log_worth,
                se=float(fit.bse[index]),
                ci=(float(intervals[index, 0]), float(intervals[index, 1])),
                worth=float(np.exp(log_worth)),
            )
        )
    return BradleyTerryResult(
        reference=reference,
        strengths=tuple(strengths),
        nobs=int(outcome.sum()),
        log_likelihood=float(fit.llf),
    )
