"""Cumulative-link (proportional-odds) mixed model of ratings, with the check of its assumption.

logit P(rating ≤ k) = θ_k − β[condition] − b_p − b_i (the parametrisation of R's
``ordinal::clmm``): a positive β means higher ratings than the reference condition.
Random intercepts for participants and items; fitted by maximum likelihood with the
Laplace approximation (clmm's default). Proportional odds is checked as
``ordinal::nominal_test`` does, by a likelihood-ratio test of the model without random
effects against one with its own thresholds per condition.
"""

from collections.abc import Sequence

import numpy as np
import pandas as pd
from scipy import stats
from statsmodels.miscmodels.ordinal_model import OrderedModel

from analysis.mixed.common import (
    coefficient,
    condition_effects,
    contrasts,
    covariance_note,
    fit_notes,
    intercepts,
    separation_note,
    standard_error,
    variance_components,
    wald_test,
)
from analysis.mixed.degenerate import check_ratings
from analysis.mixed.families import CumulativeLogit
from analysis.mixed.laplace import BOUNDARY_SD, MixedProblem, fit_laplace
from analysis.mixed.results import (
    CumulativeLinkMixedResult,
    ProportionalOddsTest,
)
from analysis.tidy import TidyFormatError, analysed


def rating_rows(frame: pd.DataFrame, question: str) -> pd.DataFrame:
    """Return one question's analysed rating rows: participant, item, condition, rating."""
    rows = frame[frame["kind"].eq("rating") & frame["question"].eq(question) & analysed(frame)]
    rows = rows[rows["rating"].notna()]
    return pd.DataFrame(
        {
            "participant": rows["participant"].to_numpy(),
            "item": rows["item"].to_numpy(),
            "condition": rows["condition_a"].to_numpy(),
            "rating": rows["rating"].to_numpy(dtype=float),
        }
    )


def rated_conditions(
    frame: pd.DataFrame, question: str, conditions: Sequence[str] | None
) -> tuple[pd.DataFrame, list[str]]:
    """Return one question's rating rows of *conditions* and the conditions rated, in order."""
    data = rating_rows(frame, question)
    order = list(conditions) if conditions else sorted(set(data["condition"]))
    data = data[data["condition"].isin(order)]
    return data, [c for c in order if c in set(data["condition"])]


def ordinal_problem(data: pd.DataFrame, conditions: Sequence[str]) -> MixedProblem:
    """Build the model from rows with participant, item, condition and rating."""
    scale = np.sort(data["rating"].unique())
    y = np.searchsorted(scale, data["rating"].to_numpy()).astype(float)
    dummies = np.column_stack([data["condition"].eq(c).to_numpy(float) for c in conditions[1:]])
    components = intercepts(data)
    return MixedProblem(
        y=y,
        X=dummies,
        fixed_names=tuple(conditions[1:]),
        components=tuple(components),
        family=CumulativeLogit(categories=len(scale)),
    )


def proportional_odds_test(data: pd.DataFrame, conditions: Sequence[str]) -> ProportionalOddsTest:
    """Test proportional odds against per-condition thresholds (as ordinal::nominal_test).

    With a condition's own thresholds, the model is a multinomial per condition whose
    maximum-likelihood fit is the observed proportions; the restricted fit is
    statsmodels' OrderedModel. LR df = (conditions − 1)(categories − 2).
    """
    scale = np.sort(data["rating"].unique())
    counts = pd.crosstab(data["condition"], data["rating"]).reindex(
        index=list(conditions), columns=scale, fill_value=0
    )
    values = counts.to_numpy(dtype=float)
    shares = values / values.sum(axis=1, keepdims=True)
    with np.errstate(divide="ignore", invalid="ignore"):
        free = float(np.nansum(np.where(values > 0, values * np.log(shares), 0.0)))
    endog = pd.Series(pd.Categorical(data["rating"], categories=scale, ordered=True), name="rating")
    exog = pd.DataFrame({c: data["condition"].eq(c).to_numpy(float) for c in conditions[1:]})
    restricted = OrderedModel(endog, exog, distr="logit").fit(method="bfgs", disp=False)
    statistic = max(2 * (free - float(restricted.llf)), 0.0)
    df = (len(conditions) - 1) * (len(scale) - 2)
    pvalue = float(stats.chi2.sf(statistic, df)) if df > 0 else float("nan")
    return ProportionalOddsTest(
        statistic=statistic, df=df, pvalue=pvalue, holds=not (pvalue < 0.05)
    )


def _notes(order, check: ProportionalOddsTest, fit, random, effects) -> list[str]:
    """Return what a reader of the model must know: its scale, proportional odds, the fit."""
    notes = [
        f"Effects are log odds ratios of rating higher than under {order[0]}.",
        "Proportional odds holds: the effects are common to every threshold."
        if check.holds
        else "Proportional odds is doubtful: report the per-threshold proportions beside "
        "the model.",
    ]
    notes += fit_notes(fit, random, fit.sd < BOUNDARY_SD)
    notes += separation_note(effects)
    notes += covariance_note(fit.cov)
    return notes


def ordinal_mixed(
    frame: pd.DataFrame,
    question: str,
    conditions: Sequence[str] | None = None,
    *,
    correction: str = "holm",
) -> CumulativeLinkMixedResult:
    """Fit the cumulative-link mixed model to one question's ratings in *frame*."""
    data, order = rated_conditions(frame, question, conditions)
    if len(order) < 2 or data["rating"].nunique() < 2:
        raise TidyFormatError(
            f"question {question!r}: an ordinal model needs ratings of two or more "
            "conditions on two or more scale points."
        )
    check_ratings(question, data)
    problem = ordinal_problem(data, order)
    fit = fit_laplace(problem)
    p = problem.X.shape[1]
    estimates, cov = fit.params[:p], fit.cov[:p, :p]
    effects, full, full_cov = condition_effects(order, estimates, cov)
    statistic, df, pvalue = wald_test(estimates, cov)
    names = problem.family.extra_names(problem.y)
    scale = np.sort(data["rating"].unique())
    thresholds = tuple(
        coefficient(
            f"{scale[k]:g}|{scale[k + 1]:g}",
            fit.params[p + k],
            standard_error(fit.cov[p + k, p + k]),
        )
        for k in range(len(names))
    )
    random = variance_components(problem.components, fit.sd)
    check = proportional_odds_test(data, order)
    notes = _notes(order, check, fit, random, effects)
    formula = f"{question} ~ condition + (1 | participant)" + (
        " + (1 | item)" if len(problem.components) > 1 else ""
    )
    return CumulativeLinkMixedResult.from_fit(
        fit,
        data,
        order,
        test=(statistic, df, pvalue),
        notes=notes,
        model="Cumulative-link mixed model (proportional odds, logit)",
        estimator="maximum likelihood, Laplace approximation (as ordinal::clmm)",
        formula=formula,
        effects=tuple(effects),
        contrasts=contrasts(order, full, full_cov, correction),
        random=random,
        correction=correction,
        question=question,
        thresholds=thresholds,
        proportional_odds=check,
    )
