"""Closed-form power of the simple cases, to check the simulation against."""

import numpy as np
from scipy import stats
from statsmodels.stats.power import TTestPower


def binomial_power(trials: int, p: float, alpha: float = 0.05) -> float:
    """Return the power of the two-sided exact binomial test of p = ½ with *trials* trials.

    Rejection region: every count whose two-sided binomial p-value (scipy's) is < alpha.
    """
    _check_binomial(p, alpha)
    if int(trials) != trials or trials < 1:
        raise ValueError(f"the number of trials must be a whole number ≥ 1, not {trials!r}")
    counts = np.arange(trials + 1)
    pvalues = np.array([stats.binomtest(int(k), trials, 0.5).pvalue for k in counts])
    return float(stats.binom.pmf(counts[pvalues < alpha], trials, p).sum())


def _check_binomial(p: float, alpha: float) -> None:
    if not 0 <= p <= 1:
        raise ValueError(f"p is a probability of choosing one clip, between 0 and 1, not {p!r}")
    if not 0 < alpha < 1:
        raise ValueError(f"alpha must lie between 0 and 1, not {alpha!r}")


def binomial_n(p: float, power: float = 0.8, alpha: float = 0.05, largest: int = 5000) -> int:
    """Return the smallest number of trials whose exact binomial test reaches *power*.

    The exact test's power is not monotone in n (it saws); this is the first n reached.
    """
    _check_binomial(p, alpha)
    for trials in range(2, largest + 1):
        if binomial_power(trials, p, alpha) >= power:
            return trials
    raise ValueError(f"power {power} is not reached within {largest} trials")


def paired_t_n(effect_size: float, power: float = 0.8, alpha: float = 0.05) -> int:
    """Return the participants a paired t-test of Cohen's d_z = *effect_size* needs."""
    n = TTestPower().solve_power(effect_size=effect_size, power=power, alpha=alpha)
    return int(np.ceil(n))


def paired_t_power(effect_size: float, participants: int, alpha: float = 0.05) -> float:
    """Return the power of a two-sided paired t-test of d_z with *participants*."""
    return float(TTestPower().power(effect_size=effect_size, nobs=participants, alpha=alpha))
