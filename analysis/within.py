"""Pairwise within-subject tests on a subjects × levels table, with multiplicity correction."""

import dataclasses
from itertools import combinations

import numpy as np
import pandas as pd
from scipy import optimize, special, stats
from statsmodels.stats.multitest import multipletests

from analysis.results import APPROXIMATE, EXACT, FriedmanResult, PairedTTest, WilcoxonTest
from analysis.summaries import PairedComparison

CORRECTIONS = {"holm": "holm", "bonferroni": "bonferroni", "fdr_bh": "fdr_bh", "none": None}


def adjust(pvalues: list[float], method: str) -> list[float]:
    """Correct *pvalues* for multiple comparisons (holm, bonferroni, fdr_bh or none)."""
    if method not in CORRECTIONS:
        raise ValueError(f"Unknown correction {method!r}; use one of {', '.join(CORRECTIONS)}.")
    if not pvalues or CORRECTIONS[method] is None:
        return list(pvalues)
    if method == "holm":
        return [float(p) for p in holm(pvalues)]
    return list(multipletests(pvalues, method=CORRECTIONS[method])[1])


def holm(pvalues) -> np.ndarray:
    """Return Holm-adjusted p-values, as statsmodels' multipletests "holm" gives them.

    Holm (1979): the i-th smallest of m p-values times m − i + 1, made non-decreasing and
    capped at 1. statsmodels' Holm branch runs gc.collect() on every call, 50–70 ms in a
    process with a large heap (a results page, a simulation, the suite); the other
    corrections go through statsmodels.
    """
    p = np.asarray(pvalues, dtype=float)
    order = np.argsort(p, kind="stable")
    stepped = np.maximum.accumulate(p[order] * np.arange(len(p), 0, -1))
    adjusted = np.empty_like(p)
    adjusted[order] = np.minimum(stepped, 1.0)
    return adjusted


def dz_interval(dz: float, n: int, level: float = 0.95) -> tuple[float, float]:
    """Return the exact CI of Cohen's d_z from the noncentral t distribution.

    Steiger & Fouladi (1997): t = d_z √n has a noncentral t distribution with n − 1
    degrees of freedom and noncentrality δ = d_z,pop √n; the limits are the δ at which
    the observed t is the upper and lower (1 − level)/2 quantile, divided by √n (as
    MBESS's ``ci.sm``).
    """
    if not np.isfinite(dz) or n < 2:
        return (float("nan"), float("nan"))
    t_value, df, tail = dz * np.sqrt(n), n - 1, (1 - level) / 2

    def limit(probability: float) -> float:
        # CDFLIB's inverse in the noncentrality (about 1e-7), polished by root-finding on
        # nct's cdf in a narrow bracket: far from the root that cdf can return NaN.
        guess = float(special.nctdtrinc(df, probability, t_value))

        def gap(ncp: float) -> float:
            return float(stats.nct.cdf(t_value, df, ncp)) - probability

        for width in (1e-4, 1e-3, 1e-2, 1e-1):
            low, high = guess - width * (1 + abs(guess)), guess + width * (1 + abs(guess))
            ends = gap(low), gap(high)
            if np.all(np.isfinite(ends)) and ends[0] * ends[1] < 0:
                return optimize.brentq(gap, low, high, xtol=1e-13)
        return guess

    return (float(limit(1 - tail) / np.sqrt(n)), float(limit(tail) / np.sqrt(n)))


def paired_ttest(a: np.ndarray, b: np.ndarray, names: tuple[str, str]) -> PairedTTest:
    """Test the mean of a − b against zero; d_z = mean(diff) / sd(diff), with its exact CI
    (:func:`dz_interval`)."""
    difference = np.asarray(a, float) - np.asarray(b, float)
    n = difference.size
    result = stats.ttest_rel(a, b)
    sd = difference.std(ddof=1)
    ci = result.confidence_interval(0.95)
    dz = float(difference.mean() / sd) if sd > 0 else float("nan")
    return PairedTTest(
        a=names[0],
        b=names[1],
        statistic=float(result.statistic),
        df=n - 1,
        pvalue=float(result.pvalue),
        pvalue_adjusted=float(result.pvalue),
        mean_difference=float(difference.mean()),
        ci=(float(ci.low), float(ci.high)),
        dz=dz,
        nobs=n,
        dz_ci=dz_interval(dz, n),
    )


def wilcoxon_test(a: np.ndarray, b: np.ndarray, names: tuple[str, str]) -> WilcoxonTest:
    """Wilcoxon signed-rank test of a − b as R's ``wilcox.test(a, b, paired = TRUE)``.

    V is the sum of the ranks of the positive differences (zeros dropped, ties given
    their mean rank); p is exact for fewer than 50 differences without ties or zeros, and
    otherwise the normal approximation with R's continuity correction and tie-corrected
    variance (Hollander & Wolfe 1973, R's defaults). r = (W⁺ − W⁻) / (W⁺ + W⁻) (Kerby 2014).
    """
    # Means of fractions (1/3 + 2/3 …) differ in their last bits: equal values must tie.
    difference = np.round(np.asarray(a, float) - np.asarray(b, float), 12)
    nonzero = difference[difference != 0]
    if difference.size < 2:
        # One participant: V = 0 and r = ±1 would read as an effect; there is no test.
        nan = float("nan")
        return WilcoxonTest(names[0], names[1], nan, nan, nan, nan, int(difference.size))
    if nonzero.size == 0:
        # Every difference is zero: R's wilcox.test gives V = 0 with p NA; no test.
        nan = float("nan")
        return WilcoxonTest(
            names[0],
            names[1],
            nan,
            nan,
            nan,
            nan,
            int(difference.size),
            note="every difference is zero",
        )
    ties = np.unique(np.abs(nonzero)).size < nonzero.size
    exact = nonzero.size < 50 and not ties and nonzero.size == difference.size
    result = stats.wilcoxon(nonzero, correction=not exact, method="exact" if exact else "approx")
    ranks = stats.rankdata(np.abs(nonzero))
    positive, negative = ranks[nonzero > 0].sum(), ranks[nonzero < 0].sum()
    return WilcoxonTest(
        a=names[0],
        b=names[1],
        statistic=float(positive),
        pvalue=float(result.pvalue),
        pvalue_adjusted=float(result.pvalue),
        rank_biserial=float((positive - negative) / (positive + negative)),
        nobs=int(difference.size),
        method=EXACT if exact else APPROXIMATE,
    )


def mean_ci(values: np.ndarray) -> tuple[float, float]:
    """Return the t-based 95 % CI of the mean of *values* (NaN for fewer than two)."""
    values = np.asarray(values, dtype=float)
    n = values.size
    if n < 2:
        return (float("nan"), float("nan"))
    half = stats.t.ppf(0.975, n - 1) * values.std(ddof=1) / np.sqrt(n)
    return (float(values.mean() - half), float(values.mean() + half))


def paired_comparisons(wide: pd.DataFrame, result: type[PairedComparison], **fields) -> list:
    """Return a *result* (paired t and Wilcoxon tests) for every two columns of *wide*
    (participants × conditions) that two or more participants have both, naming who has
    only one of them; *fields* are the result's other fields (item, question, measure)."""
    found = []
    for a, b in combinations(sorted(wide.columns), 2):
        paired = wide[[a, b]].dropna()
        if len(paired) < 2:
            continue
        # Who answered in only one of the two is not in the tests: the result names them.
        one = wide[[a, b]].notna().sum(axis=1) == 1
        x, y = paired[a].to_numpy(), paired[b].to_numpy()
        found.append(
            result(
                a=a,
                b=b,
                nobs=len(paired),
                wilcoxon=wilcoxon_test(x, y, (a, b)),
                ttest=paired_ttest(x, y, (a, b)),
                left_out=tuple(str(who) for who in wide.index[one]),
                **fields,
            )
        )
    return found


def adjust_comparisons(comparisons: list, correction: str) -> tuple:
    """Return *comparisons* with each test's p-values corrected across them."""
    wilcoxon = adjust([c.wilcoxon.pvalue for c in comparisons], correction)
    ttest = adjust([c.ttest.pvalue for c in comparisons], correction)
    return tuple(
        dataclasses.replace(
            c,
            wilcoxon=dataclasses.replace(c.wilcoxon, pvalue_adjusted=float(pw)),
            ttest=dataclasses.replace(c.ttest, pvalue_adjusted=float(pt)),
        )
        for c, pw, pt in zip(comparisons, wilcoxon, ttest, strict=True)
    )


def _pairwise(scores: pd.DataFrame, test, correction: str) -> tuple:
    scores = scores.dropna()
    results = [
        test(scores[a].to_numpy(), scores[b].to_numpy(), (str(a), str(b)))
        for a, b in combinations(scores.columns, 2)
    ]
    adjusted = adjust([r.pvalue for r in results], correction)
    return tuple(
        dataclasses.replace(r, pvalue_adjusted=float(p))
        for r, p in zip(results, adjusted, strict=True)
    )


def paired_ttests(scores: pd.DataFrame, correction: str = "holm") -> tuple[PairedTTest, ...]:
    """Run a paired t-test for every pair of levels, correcting across pairs."""
    return _pairwise(scores, paired_ttest, correction)


def wilcoxon_tests(scores: pd.DataFrame, correction: str = "holm") -> tuple[WilcoxonTest, ...]:
    """Run a Wilcoxon signed-rank test for every pair of levels, correcting across pairs."""
    return _pairwise(scores, wilcoxon_test, correction)


def friedman(scores: pd.DataFrame) -> FriedmanResult:
    """Friedman test over the levels; Kendall's W = χ² / (n (k − 1))."""
    scores = scores.dropna()
    n, k = scores.shape
    result = stats.friedmanchisquare(*(scores[column].to_numpy() for column in scores.columns))
    return FriedmanResult(
        statistic=float(result.statistic),
        df=k - 1,
        pvalue=float(result.pvalue),
        kendall_w=float(result.statistic / (n * (k - 1))),
        nobs=n,
    )
