"""Linear mixed model of ratings as numbers, for researchers who report means.

rating = μ + β[condition] + b_p + b_i + ε with crossed random intercepts for
participants and items (and, on request, participants' own condition effects, correlated
with their intercepts), fitted by REML or ML (analysis.mixed.lmm) like
``lmerTest::lmer(rating ~ condition + (1 | participant) + (1 | item))``: t and F tests
with Satterthwaite's df, the likelihood-ratio test of ``anova(m0, m1)`` and profile CIs
of the SDs.
"""

from collections.abc import Sequence

import numpy as np
import pandas as pd
from scipy import stats

from analysis.mixed.common import (
    codes,
    condition_effects,
    contrasts,
    fit_notes,
    intercepts,
)
from analysis.mixed.degenerate import check_ratings
from analysis.mixed.lmm import LinearFit, fit_lmm
from analysis.mixed.ordinal import rated_conditions
from analysis.mixed.problem import Component, MixedProblem
from analysis.mixed.profile import sd_intervals
from analysis.mixed.results import (
    Correlation,
    LikelihoodRatioTest,
    LinearMixedResult,
    VarianceComponent,
)
from analysis.mixed.satterthwaite import Satterthwaite
from analysis.tidy import CONTINUOUS, TidyFormatError, rating_scale

SLOPES = "(condition | participant)"


def slopes_identifiable(data: pd.DataFrame, conditions: Sequence[str]) -> str:
    """Return why participants' own condition effects cannot be estimated ("" if they can).

    Each participant must have rated every condition, there must be five or more of
    them, and more ratings than random effects (lme4's check).
    """
    seen = data.groupby("participant")["condition"].nunique()
    complete = int((seen == len(conditions)).sum())
    if complete < len(seen) or complete < 5:
        return (
            f"participants' own condition effects {SLOPES} need five or more participants "
            f"who each rated every condition; {complete} of {len(seen)} did"
        )
    effects = len(seen) * len(conditions) + data["item"].nunique()
    if len(data) <= effects:
        return (
            f"participants' own condition effects {SLOPES} need more ratings ({len(data)}) "
            f"than random effects ({effects})"
        )
    return ""


def _problem(data, order, *, with_conditions: bool, slopes: bool) -> MixedProblem:
    dummies = [data["condition"].eq(c).to_numpy(float) for c in order[1:]]
    X = np.column_stack([np.ones(len(data)), *(dummies if with_conditions else [])])
    components = intercepts(data)
    if slopes:
        participant, levels = codes(data["participant"])
        components[0] = Component.from_codes(
            "participant",
            "participant",
            participant,
            levels,
            values=np.column_stack([np.ones(len(data)), *dummies]),
            columns=("(Intercept)", *order[1:]),
            correlated=True,
        )
    return MixedProblem(
        y=data["rating"].to_numpy(float),
        X=X,
        fixed_names=("(Intercept)", *order[1:]) if with_conditions else ("(Intercept)",),
        components=tuple(components),
    )


def _random(problem: MixedProblem, fit: LinearFit, intervals) -> tuple[VarianceComponent, ...]:
    levels = {c.name: len(c.levels) for c in problem.components}
    groups = {c.name: c.group for c in problem.components}
    return tuple(
        VarianceComponent(
            name=name,
            group=groups[name],
            sd=float(sd),
            variance=float(sd**2),
            levels=levels[name],
            column=column,
            ci=ci,
        )
        for (name, column), sd, ci in zip(fit.columns, fit.sd, intervals, strict=True)
    )


def likelihood_ratio(
    data, order, *, slopes: bool, full: LinearFit | None = None
) -> LikelihoodRatioTest:
    """Test that the conditions are alike by ML fits with and without them (R's anova).

    *full* is the ML fit with the conditions, where the caller has it.
    """
    if full is None:
        full = fit_lmm(_problem(data, order, with_conditions=True, slopes=slopes), reml=False)
    reduced = fit_lmm(_problem(data, order, with_conditions=False, slopes=slopes), reml=False)
    statistic = max(2 * (full.loglik - reduced.loglik), 0.0)
    df = len(order) - 1
    return LikelihoodRatioTest(
        reduced="rating ~ 1 + random effects",
        full="rating ~ condition + random effects",
        statistic=statistic,
        df=df,
        pvalue=float(stats.chi2.sf(statistic, df)),
        loglik_reduced=reduced.loglik,
        loglik_full=full.loglik,
    )


def _notes(problem, fit, random, order: Sequence[str], reason: str, scale: str) -> list[str]:
    """Return what a reader of the linear model must know: its scale, its tests, and
    which random effects the data could not support."""
    treated = (
        "ratings are on a continuous scale (a slider), so no ordinal model is fitted."
        if scale == CONTINUOUS
        else "ratings are treated as interval numbers (see the ordinal model for the "
        "ordered-category analysis)."
    )
    notes = [
        f"Effects are differences of mean rating from {order[0]}; {treated}",
        "t and F tests use Satterthwaite's degrees of freedom (as lmerTest).",
    ]
    if reason:
        notes.append(f"Intercepts only: {reason}.")
    correlated = {c.name for c in problem.components if c.correlated}
    at_zero = [c.name in fit.singular_components and c.name not in correlated for c in random]
    notes += fit_notes(fit, random, at_zero)
    for name in sorted(correlated & set(fit.singular_components)):
        notes.append(
            f"Singular (boundary) fit: the covariance of the {name} random effects "
            "(intercept and condition effects) is singular — a variance at zero or a "
            f"correlation at ±1 — so the data cannot support {SLOPES}; fit intercepts only."
        )
    return notes


# How the model was fitted, by whether it was REML (True) or maximum likelihood.
ESTIMATORS = {
    True: "REML, lme4::lmer's profiled criterion",
    False: "maximum likelihood, lme4::lmer(REML = FALSE)",
}


def _contrast_df(satterthwaite: Satterthwaite, n_beta: int):
    """Return the Satterthwaite df of condition j's effect (i = 0) or of j − i."""

    def df_of(i: int, j: int) -> float:
        row = np.zeros(n_beta)
        row[j] = 1.0
        if i:
            row[i] = -1.0
        return satterthwaite.df(row)

    return df_of


def _checked(question: str, data: pd.DataFrame, order: Sequence[str], slopes) -> str:
    """Check that the ratings can be modelled; return why participants' condition effects
    cannot be identified ("" where they can, or were not asked for)."""
    if len(order) < 2 or data["participant"].nunique() < 2:
        raise TidyFormatError(
            f"question {question!r}: a linear mixed model needs ratings of two or more "
            "conditions by two or more participants."
        )
    check_ratings(question, data)
    reason = slopes_identifiable(data, order) if slopes is not False else ""
    if slopes and reason:
        raise TidyFormatError(f"question {question!r}: {reason}.")
    return reason


def linear_mixed(
    frame: pd.DataFrame,
    question: str,
    conditions: Sequence[str] | None = None,
    *,
    correction: str = "holm",
    reml: bool = True,
    slopes: bool | None = False,
    sd_ci: bool = True,
) -> LinearMixedResult:
    """Fit the linear mixed model to one question's ratings in *frame*.

    ``reml=False`` fits by maximum likelihood. ``slopes=True`` adds participants' own
    condition effects, correlated with their intercepts (an error naming why where the
    design cannot identify them); ``None`` adds them where it can. ``sd_ci`` computes
    profile CIs of the SDs (intercept-only models).
    """
    data, order = rated_conditions(frame, question, conditions)
    reason = _checked(question, data, order, slopes)
    slopes = slopes is not False and not reason
    problem = _problem(data, order, with_conditions=True, slopes=slopes)
    fit = fit_lmm(problem, reml=reml)
    width = len(order) - 1
    satterthwaite = Satterthwaite.of(fit)
    df_of = _contrast_df(satterthwaite, len(fit.beta))
    estimates, cov = fit.beta[1 : 1 + width], fit.cov[1 : 1 + width, 1 : 1 + width]
    effects, full, full_cov = condition_effects(order, estimates, cov, df_of)
    statistic, df, den_df, pvalue = satterthwaite.f_test(np.eye(len(fit.beta))[1:], fit.beta)
    # The ML fit serves the profile CIs (lme4 profiles the ML deviance) and the LR test.
    ml = fit if not reml else fit_lmm(problem, reml=False)
    intervals = sd_intervals(ml) if sd_ci else [None] * (len(fit.sd) + 1)
    random = _random(problem, fit, intervals[:-1])
    notes = _notes(problem, fit, random, order, reason, rating_scale(frame, question))
    formula = f"{question} ~ condition + " + " + ".join(
        f"(1 + condition | {c.name})" if c.correlated else f"(1 | {c.name})"
        for c in problem.components
    )
    return LinearMixedResult.from_fit(
        fit,
        data,
        order,
        test=(statistic, df, pvalue),
        n_params=len(fit.beta) + len(fit.theta) + 1,
        notes=notes,
        model="Linear mixed model",
        estimator=ESTIMATORS[reml],
        formula=formula,
        effects=tuple(effects),
        contrasts=contrasts(order, full, full_cov, correction, df_of),
        random=random,
        correction=correction,
        question=question,
        residual_sd=fit.sigma,
        residual_sd_ci=intervals[-1],
        reml=reml,
        den_df=den_df,
        likelihood_ratio=likelihood_ratio(data, order, slopes=slopes, full=ml),
        correlations=tuple(Correlation(g, a, b, r) for g, a, b, r in fit.correlations),
    )
