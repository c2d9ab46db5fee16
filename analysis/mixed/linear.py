"""Linear mixed model of ratings as numbers, for researchers who report means.

rating = μ + β[condition] + b_p + b_i + ε with crossed random intercepts for
participants and items, fitted by REML with statsmodels' MixedLM (its variance
components over one all-encompassing group give crossed effects), like
``lme4::lmer(rating ~ condition + (1 | participant) + (1 | item))``.
"""

import warnings
from collections.abc import Sequence

import numpy as np
import pandas as pd
import statsmodels.formula.api as smf
from statsmodels.tools.sm_exceptions import ConvergenceWarning

from analysis.mixed.common import condition_effects, contrasts, wald_test
from analysis.mixed.laplace import BOUNDARY_SD
from analysis.mixed.ordinal import rated_conditions
from analysis.mixed.results import LinearMixedResult, VarianceComponent
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
    groups = {"participant": "0 + C(participant)"}
    if data["item"].nunique() > 1:
        groups["item"] = "0 + C(item)"
    levels = "[" + ", ".join(repr(c) for c in order) + "]"
    model = smf.mixedlm(
        f"rating ~ C(condition, levels={levels})",
        data.assign(everyone=1),
        groups="everyone",
        re_formula="0",
        vc_formula=groups,
    )
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", ConvergenceWarning)
        fit = model.fit(reml=True)
    estimates = np.asarray(fit.fe_params)[1:]
    cov = np.asarray(fit.cov_params())[1 : len(order), 1 : len(order)]
    effects, full, full_cov = condition_effects(order, estimates, cov)
    statistic, df, pvalue = wald_test(estimates, cov)
    # MixedLM orders the variance components by name.
    names = sorted(groups)
    sds = dict(zip(names, np.sqrt(np.asarray(fit.vcomp)), strict=True))
    random = tuple(
        VarianceComponent(
            name=name,
            group=name,
            sd=float(sds[name]),
            variance=float(sds[name] ** 2),
            levels=int(data[name].nunique()),
        )
        for name in groups
    )
    notes = [
        f"Effects are differences of mean rating from {order[0]}; ratings are treated "
        "as interval numbers (see the ordinal model for the ordered-category analysis).",
        "p-values are Wald z tests, as statsmodels reports them (no Satterthwaite df).",
    ]
    notes += [
        f"The {c.name} SD is estimated at zero (a boundary fit)."
        for c in random
        if c.sd < BOUNDARY_SD
    ]
    converged = bool(fit.converged) and not any(
        issubclass(w.category, ConvergenceWarning) for w in caught
    )
    if not converged:
        notes.append("statsmodels warned that the fit may not have converged.")
    return LinearMixedResult(
        model="Linear mixed model",
        estimator="REML (statsmodels MixedLM, as lme4::lmer)",
        formula=f"{question} ~ condition + " + " + ".join(f"(1 | {name})" for name in groups),
        conditions=tuple(order),
        reference=order[0],
        effects=tuple(effects),
        contrasts=contrasts(order, full, full_cov, correction),
        random=random,
        statistic=statistic,
        df=df,
        pvalue=pvalue,
        nobs=int(fit.nobs),
        participants=int(data["participant"].nunique()),
        items=int(data["item"].nunique()),
        loglik=float(fit.llf),
        aic=float(-2 * fit.llf + 2 * (len(order) + len(groups) + 1)),
        converged=converged,
        correction=correction,
        notes=tuple(notes),
        question=question,
        residual_sd=float(np.sqrt(fit.scale)),
    )
