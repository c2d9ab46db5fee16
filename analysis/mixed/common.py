"""Turn a Laplace or statsmodels fit into coefficients, contrasts and the omnibus test."""

from collections.abc import Sequence
from itertools import combinations

import numpy as np
import pandas as pd
from scipy import stats

from analysis.mixed.convergence import singular_note
from analysis.mixed.problem import Component, LaplaceFit
from analysis.mixed.results import Coefficient, Contrast, VarianceComponent
from analysis.within import adjust


def standard_error(variance: float) -> float:
    """Return √variance, or NaN where a covariance that is not positive definite gave < 0."""
    return float(np.sqrt(variance)) if variance >= 0 else float("nan")


def covariance_note(cov: np.ndarray) -> list[str]:
    """Say so when a fit's covariance has no valid variances (an unidentified fit)."""
    if np.all(np.diag(cov) > 0):
        return []
    return [
        "Some standard errors are unavailable: the fit's covariance is not positive "
        "definite (too few participants, or a variance at its boundary); treat its "
        "tests as unreliable."
    ]


def coefficient(name: str, estimate: float, se: float, df: float | None = None) -> Coefficient:
    """Return a Wald z test and 95 % CI of one estimate, or a t test on *df* df."""
    statistic = estimate / se if se > 0 else np.nan
    law = stats.norm if df is None else stats.t(df)
    pvalue = 2 * law.sf(abs(statistic)) if np.isfinite(statistic) else np.nan
    half = float(law.ppf(0.975)) * se
    return Coefficient(
        name=name,
        estimate=float(estimate),
        se=float(se),
        statistic=float(statistic),
        pvalue=float(pvalue),
        ci=(float(estimate - half), float(estimate + half)),
        df=None if df is None else float(df),
    )


def condition_effects(
    conditions: Sequence[str], estimates: np.ndarray, cov: np.ndarray, df_of=None
) -> tuple[list[Coefficient], np.ndarray, np.ndarray]:
    """Return the non-reference conditions' coefficients and the full effect vector/cov.

    *estimates* and *cov* cover conditions[1:]; the reference's effect is 0 exactly.
    ``df_of(0, j)``, where given, is the df of condition j's t test.
    """
    coefficients = [
        coefficient(
            condition,
            estimates[i],
            standard_error(cov[i, i]),
            None if df_of is None else df_of(0, i + 1),
        )
        for i, condition in enumerate(conditions[1:])
    ]
    full = np.concatenate([[0.0], estimates])
    full_cov = np.zeros((len(conditions), len(conditions)))
    full_cov[1:, 1:] = cov
    return coefficients, full, full_cov


def contrasts(
    conditions: Sequence[str], effects: np.ndarray, cov: np.ndarray, correction: str, df_of=None
) -> tuple[Contrast, ...]:
    """Return every pair's difference b − a (a before b in *conditions*), corrected.

    ``df_of(i, j)``, where given, is the df of the t test of conditions i and j.
    """
    rows = []
    for i, j in combinations(range(len(conditions)), 2):
        estimate = effects[j] - effects[i]
        variance = cov[i, i] + cov[j, j] - 2 * cov[i, j]
        df = None if df_of is None else df_of(i, j)
        rows.append(
            (conditions[j], conditions[i], coefficient("", estimate, standard_error(variance), df))
        )
    adjusted = adjust([c.pvalue for _, _, c in rows], correction) if rows else []
    return tuple(
        Contrast(
            a=a,
            b=b,
            estimate=c.estimate,
            se=c.se,
            statistic=c.statistic,
            pvalue=c.pvalue,
            pvalue_adjusted=float(p_adj),
            ci=c.ci,
            df=c.df,
        )
        for (a, b, c), p_adj in zip(rows, adjusted, strict=True)
    )


def wald_test(estimates: np.ndarray, cov: np.ndarray) -> tuple[float, int, float]:
    """Return the Wald χ² that all *estimates* are zero, its df and p."""
    try:
        statistic = float(estimates @ np.linalg.solve(cov, estimates))
    except np.linalg.LinAlgError:
        return np.nan, len(estimates), np.nan
    return statistic, len(estimates), float(stats.chi2.sf(statistic, len(estimates)))


def codes(values: pd.Series) -> tuple[np.ndarray, tuple[str, ...]]:
    """Return integer codes and the sorted levels of a column."""
    levels, inverse = np.unique(np.asarray(values), return_inverse=True)
    return inverse.astype(np.int64), tuple(levels.tolist())


def intercepts(data: pd.DataFrame) -> list[Component]:
    """Return random intercepts for participants, and for items when there are several."""
    participant, participant_levels = codes(data["participant"])
    components = [
        Component.from_codes("participant", "participant", participant, participant_levels)
    ]
    item, item_levels = codes(data["item"])
    if len(item_levels) > 1:
        components.append(Component.from_codes("item", "item", item, item_levels))
    return components


def variance_components(
    components: Sequence[Component], sds: np.ndarray
) -> tuple[VarianceComponent, ...]:
    """Return each component's fitted SD with its variance and number of levels."""
    return tuple(
        VarianceComponent(
            name=c.name, group=c.group, sd=float(sd), variance=float(sd**2), levels=len(c.levels)
        )
        for c, sd in zip(components, sds, strict=True)
    )


def fit_notes(fit: LaplaceFit, random: Sequence[VarianceComponent], at_zero) -> list[str]:
    """Return the notes every mixed model carries: a singular fit, failed checks.

    *at_zero* says which of the *random* components sit on their bound (by lme4's θ).
    """
    notes = []
    zero = [c.name for c, flag in zip(random, at_zero, strict=True) if flag]
    if fit.singular and zero:
        notes.append(singular_note(zero))
    notes += [f"{message[0].upper()}{message[1:]}." for message in fit.checks]
    if not fit.converged and not fit.checks:
        notes.append(f"The optimiser did not report convergence: {fit.message}")
    return notes


def separation_note(effects: Sequence[Coefficient]) -> list[str]:
    """Name effects that run off to infinity: choices or ratings separated by condition.

    On the logit scale an estimate beyond ±10 (odds of 22,000 to 1) with no usable SE
    means the likelihood rises without bound (lme4 and clmm print such numbers too).
    """
    runaway = [c.name for c in effects if abs(c.estimate) > 10 and not c.se < abs(c.estimate) / 2]
    if not runaway:
        return []
    return [
        f"The estimate of {', '.join(runaway)} is unbounded: the answers are (nearly) "
        "separated by condition (one always chosen, or always rated higher), so the "
        "estimate and its test are not meaningful; report the counts instead."
    ]
