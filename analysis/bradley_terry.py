"""Fit Bradley–Terry strengths to paired-comparison counts by logistic regression."""

from collections.abc import Sequence

import numpy as np
import pandas as pd
import statsmodels.api as sm
from scipy.sparse import csr_matrix
from scipy.sparse.csgraph import connected_components

from analysis.results import BradleyTerryResult, Strength


def bradley_terry(counts: pd.DataFrame, conditions: Sequence[str]) -> BradleyTerryResult:
    """Return each condition's log-worth relative to ``conditions[0]`` (fixed at 0).

    *counts* has columns ``a, b, a_wins, b_wins``. Model: logit P(a beats b) = β_a − β_b
    (Bradley & Terry 1952), fitted as a binomial GLM without intercept; CIs are Wald 95 %.
    Where the strengths have no finite estimate (:func:`not_estimable`) the result holds
    none and says why, as R's ``glm`` gives NA for an aliased condition: a pseudo-inverse
    would print an arbitrary split with finite SEs.
    """
    conditions = list(conditions)
    reference, others = conditions[0], conditions[1:]
    counts = counts[(counts["a_wins"] + counts["b_wins"]) > 0]
    problem = not_estimable(counts, conditions)
    if problem:
        nobs = int(counts[["a_wins", "b_wins"]].to_numpy().sum())
        return BradleyTerryResult(reference, (), nobs, float("nan"), not_estimable=problem)
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


def not_estimable(counts: pd.DataFrame, conditions: Sequence[str]) -> str:
    """Return why the strengths of *conditions* have no finite estimate ("" if they have).

    They have one exactly when, for every split of the conditions into two groups, each
    group beat the other at least once (Ford 1957): the graph of "a beat b" is strongly
    connected. If the conditions were not all compared, directly or through others, the
    split between them is not identified at all (the design's graph is disconnected); if
    they were but one group never beat (or never lost to) the rest, the likelihood rises
    without bound as their difference grows (separation).
    """
    index = {c: k for k, c in enumerate(conditions)}
    beat = np.zeros((len(conditions), len(conditions)))
    for a, b, a_wins, b_wins in counts[["a", "b", "a_wins", "b_wins"]].itertuples(index=False):
        beat[index[a], index[b]] += a_wins
        beat[index[b], index[a]] += b_wins
    graph = csr_matrix(beat > 0)
    parts, labels = connected_components(graph, directed=False)
    if parts > 1:
        groups = "; ".join(_group(conditions, labels, k) for k in range(parts))
        return (
            "the conditions were not all compared with one another, directly or through "
            f"others (separate groups: {groups}), so the strengths of one group relative "
            "to another are not identified"
        )
    parts, labels = connected_components(graph, directed=True, connection="strong")
    if parts > 1:
        losers = [k for k in range(parts) if not _beats_outside(beat, labels, k)]
        return (
            f"{_group(conditions, labels, losers[0])} never beat any other condition it "
            "was compared with (separation: the strengths have no finite "
            "maximum-likelihood estimate)"
        )
    return ""


def _group(conditions: Sequence[str], labels: np.ndarray, label: int) -> str:
    return ", ".join(c for c, k in zip(conditions, labels, strict=True) if k == label)


def _beats_outside(beat: np.ndarray, labels: np.ndarray, label: int) -> bool:
    inside = labels == label
    return bool(beat[np.ix_(inside, ~inside)].sum() > 0)
