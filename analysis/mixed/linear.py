"""Linear mixed model of ratings as numbers, for researchers who report means.

rating = μ + β[condition] + b_p + b_i + ε with crossed random intercepts for
participants and items, fitted by REML (analysis.mixed.reml) like
``lme4::lmer(rating ~ condition + (1 | participant) + (1 | item))``.
"""

from collections.abc import Sequence

import numpy as np
import pandas as pd

from analysis.mixed.common import (
    condition_effects,
    contrasts,
    intercepts,
    variance_components,
    wald_test,
)
from analysis.mixed.laplace import BOUNDARY_SD, MixedProblem
from analysis.mixed.ordinal import rated_conditions
from analysis.mixed.reml import fit_reml
from analysis.mixed.results import LinearMixedResult
from analysis.tidy import TidyFormatError


def linear_mixed(
    frame: pd.DataFrame,
    question: str,
    conditions: Sequence[str] | None = None,
    *,
    correction: str = "holm",
) -> LinearMixedResult:
    """Fit the linear mixed model to one question's ratings in *frame* by REML."""
    data, order = rated_conditions(frame, question, conditions)
    if len(order) < 2 or data["participant"].nunique() < 2:
        raise TidyFormatError(
            f"question {question!r}: a linear mixed model needs ratings of two or more "
            "conditions by two or more participants."
        )
    components = intercepts(data)
    dummies = [data["condition"].eq(c).to_numpy(float) for c in order[1:]]
    problem = MixedProblem(
        y=data["rating"].to_numpy(float),
        X=np.column_stack([np.ones(len(data)), *dummies]),
        fixed_names=("(Intercept)", *order[1:]),
        components=tuple(components),
    )
    fit = fit_reml(problem)
    width = len(order) - 1
    estimates, cov = fit.params[1 : 1 + width], fit.cov[1 : 1 + width, 1 : 1 + width]
    effects, full, full_cov = condition_effects(order, estimates, cov)
    statistic, df, pvalue = wald_test(estimates, cov)
    random = variance_components(components, fit.sd)
    notes = [
        f"Effects are differences of mean rating from {order[0]}; ratings are treated "
        "as interval numbers (see the ordinal model for the ordered-category analysis).",
        "p-values are Wald z tests (no Satterthwaite or Kenward–Roger df).",
    ]
    notes += [
        f"The {c.name} SD is estimated at zero (a boundary fit)."
        for c in random
        if c.sd < BOUNDARY_SD
    ]
    converged = fit.converged
    if not converged:
        notes.append(f"The optimiser did not report convergence: {fit.message}")
    return LinearMixedResult(
        model="Linear mixed model",
        estimator="REML, lme4::lmer's profiled criterion",
        formula=f"{question} ~ condition + " + " + ".join(f"(1 | {c.name})" for c in components),
        conditions=tuple(order),
        reference=order[0],
        effects=tuple(effects),
        contrasts=contrasts(order, full, full_cov, correction),
        random=random,
        statistic=statistic,
        df=df,
        pvalue=pvalue,
        nobs=fit.nobs,
        participants=int(data["participant"].nunique()),
        items=int(data["item"].nunique()),
        loglik=fit.loglik,
        aic=-2 * fit.loglik + 2 * (len(order) + len(components) + 1),
        converged=converged,
        correction=correction,
        notes=tuple(notes),
        question=question,
        residual_sd=float(fit.params[-1]),
    )
