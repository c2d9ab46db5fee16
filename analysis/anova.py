"""One-way repeated-measures ANOVA with Mauchly's test and the Greenhouse–Geisser and
Huynh–Feldt corrections."""

import numpy as np
import pandas as pd
from scipy import stats
from statsmodels.stats.anova import AnovaRM

from analysis.results import RmAnovaResult, few_named


def orthonormal_contrasts(k: int) -> np.ndarray:
    """Return a (k−1, k) matrix of orthonormal contrasts (rows orthogonal to ones)."""
    # Helmert-style contrasts, normalized: any orthonormal basis of the contrast space
    # gives the same sphericity statistics.
    contrasts = np.zeros((k - 1, k))
    for row in range(k - 1):
        contrasts[row, : row + 1] = 1.0
        contrasts[row, row + 1] = -(row + 1)
        contrasts[row] /= np.linalg.norm(contrasts[row])
    return contrasts


def sphericity(scores: np.ndarray) -> tuple[float, float, float]:
    """Return Mauchly's W, its p-value, and the Greenhouse–Geisser epsilon.

    *scores* is (n_subjects, k_levels); with two levels W and p are NaN (no test) and ε
    is 1. Formulas: Mauchly (1940) W = det(S) / (tr(S)/p)^p with p = k − 1 and S the
    covariance of orthonormal contrasts; Greenhouse & Geisser (1959) ε = tr(S)² /
    (p tr(S²)), bounded to [1/p, 1].
    """
    k = scores.shape[1]
    if k < 3:
        # Two levels: sphericity holds trivially and there is nothing to test.
        return float("nan"), float("nan"), 1.0
    return contrast_sphericity(scores @ orthonormal_contrasts(k).T, k)


def contrast_sphericity(transformed: np.ndarray, k: int) -> tuple[float, float, float]:
    """Return Mauchly's W, its p and the Greenhouse–Geisser ε of (n, p) scores on p
    orthonormal contrasts (:func:`sphericity`'s formulas); *k* enters the p-value's
    second-order term as R's mauchly.test takes it (the levels; the term vanishes for
    p = 2)."""
    n, p = transformed.shape
    if p < 2:
        return float("nan"), float("nan"), 1.0
    covariance = np.atleast_2d(np.cov(transformed, rowvar=False, ddof=1))
    trace = np.trace(covariance)
    epsilon = trace**2 / (p * np.trace(covariance @ covariance)) if trace > 0 else 1.0
    determinant = np.linalg.det(covariance)
    if trace <= 0 or determinant <= 0 or n - 1 < p:
        return float("nan"), float("nan"), float(min(max(epsilon, 1 / p), 1.0))
    w = determinant / (trace / p) ** p
    # χ² approximation with the second-order term of Anderson (2003) §10.7, as in R's
    # mauchly.test (which uses the number of levels k in the w2 term).
    df_resid = n - 1
    rho = 1 - (2 * p**2 + p + 2) / (6 * p * df_resid)
    w2 = (
        (p + 2)
        * (p - 1)
        * (p - 2)
        * (2 * p**3 + 6 * p**2 + 3 * k + 2)
        / (288 * (df_resid * p * rho) ** 2)
    )
    chi2 = -df_resid * rho * np.log(w)
    dof = p * (p + 1) / 2 - 1
    first, second = stats.chi2.sf(chi2, dof), stats.chi2.sf(chi2, dof + 4)
    pvalue = first + w2 * (second - first)
    return float(w), float(pvalue), float(min(max(epsilon, 1 / p), 1.0))


def corrected_pvalue(f_value: float, df_num: float, df_den: float, epsilon: float) -> float:
    """Return the p of F on both degrees of freedom scaled by a sphericity ε."""
    return float(stats.f.sf(f_value, epsilon * df_num, epsilon * df_den))


def huynh_feldt(epsilon_gg: float, n: int, k: int) -> float:
    """Return the Huynh–Feldt epsilon from the Greenhouse–Geisser one, at most 1.

    Huynh & Feldt (1976), as R's ``anova.mlm`` computes it for one group:
    ε̃ = (n p ε̂ − 2) / (p (n − 1 − p ε̂)) with p = k − 1 and n subjects.
    """
    p = k - 1
    if p < 2:
        return 1.0
    denominator = p * (n - 1 - p * epsilon_gg)
    if denominator <= 0:
        return 1.0
    return float(min((n * p * epsilon_gg - 2) / denominator, 1.0))


def rm_anova(scores: pd.DataFrame) -> RmAnovaResult:
    """Test whether the level means of a subjects × levels table differ.

    The F test is statsmodels' ``AnovaRM``; sphericity and effect size are added:
    ``eta_p2 = SS_effect / (SS_effect + SS_error) = F·df1 / (F·df1 + df2)``. Subjects
    without a score at every level are left out and named in ``notes``; where the
    error variance is zero the F test is undefined, and the result says why instead of
    giving a number.
    """
    notes = []
    missing = scores.index[scores.isna().any(axis=1)]
    if len(missing):
        notes.append(
            f"{len(missing)} subject(s) without a score at every level are left out "
            f"({few_named(missing)})."
        )
    scores = scores.dropna()
    n, k = scores.shape
    if n < 2 or k < 2:
        raise ValueError(f"A repeated-measures ANOVA needs ≥ 2 subjects and levels; got {n}×{k}.")
    values = scores.to_numpy(dtype=float)
    residual = values - values.mean(axis=1, keepdims=True) - values.mean(axis=0) + values.mean()
    ss_error = float(np.sum(residual**2))
    ss_effect = float(n * np.sum((values.mean(axis=0) - values.mean()) ** 2))
    levels = tuple(str(level) for level in scores.columns)
    if ss_error <= 1e-12 * max(ss_effect + ss_error, np.sum(values**2), 1e-300):
        notes.append(
            "Every subject's scores are the same at every level: there is no variance to test."
            if ss_effect <= 1e-12 * max(np.sum(values**2), 1e-300)
            else "The error variance is zero (every subject's scores differ between levels "
            "by the same amounts), so F is undefined: report the level means, not a test."
        )
        nan = float("nan")
        return RmAnovaResult(
            nan, k - 1.0, (n - 1.0) * (k - 1), nan, nan, nan, nan, nan, nan, n, levels, tuple(notes)
        )
    long = scores.rename_axis(index="subject", columns="level").stack().rename("value")
    table = AnovaRM(long.reset_index(), "value", "subject", within=["level"]).fit().anova_table
    f_value = float(table["F Value"].iloc[0])
    df_num = float(table["Num DF"].iloc[0])
    df_den = float(table["Den DF"].iloc[0])
    w, w_p, epsilon = sphericity(values)
    epsilon_hf = huynh_feldt(epsilon, n, k)
    return RmAnovaResult(
        statistic=f_value,
        df_num=df_num,
        df_den=df_den,
        pvalue=float(table["Pr > F"].iloc[0]),
        epsilon_gg=epsilon,
        pvalue_gg=corrected_pvalue(f_value, df_num, df_den, epsilon),
        eta_p2=f_value * df_num / (f_value * df_num + df_den),
        mauchly_w=w,
        mauchly_pvalue=w_p,
        nobs=n,
        levels=levels,
        notes=tuple(notes),
        epsilon_hf=epsilon_hf,
        pvalue_hf=corrected_pvalue(f_value, df_num, df_den, epsilon_hf),
    )
