"""Profile-likelihood confidence intervals for a linear mixed model's SDs (lme4's ``confint``).

The deviance is written in the SDs ψ = (σ₁ … σ_k, σ), θ_k = σ_k/σ; for one of them
held at c the others are re-optimised, and the 95 % interval is where the profiled
deviance exceeds its minimum by χ²₁(0.95) = 3.84 (Bates et al. 2015 §5.1;
``confint(fit, method = "profile")``). As lme4 1.1-31 does, the profile is of the ML
deviance, for a REML fit too (its intervals are the same for both fits). A lower limit is
0 where the deviance at 0 is within that distance. Components with correlated columns
are not profiled.
"""

import numpy as np
from scipy import optimize as scipy_optimize
from scipy import stats

from analysis.mixed import optimize
from analysis.mixed.lmm import LinearFit, fit_lmm

CUTOFF = float(stats.chi2.ppf(0.95, 1))


def sd_intervals(fit: LinearFit) -> list[tuple[float, float] | None]:
    """Return a 95 % CI per random-effect SD of *fit* and, last, the residual SD's."""
    if any(component.correlated for component in fit.criterion.problem.components):
        return [None] * (len(fit.sd) + 1)
    if fit.reml:
        fit = fit_lmm(fit.criterion.problem, reml=False)
    criterion = fit.criterion
    estimate = np.concatenate([fit.theta * fit.sigma, [fit.sigma]])
    k = len(fit.theta)

    def deviance(psi: np.ndarray) -> float:
        sigma = psi[-1]
        if sigma <= 0:
            return np.inf
        return criterion.deviance(np.concatenate([psi[:-1] / sigma, [sigma]]))

    minimum = deviance(estimate)
    lower = np.concatenate([np.zeros(k), [1e-3 * fit.sigma]])
    upper = np.full(k + 1, np.inf)
    step = np.maximum(0.1 * estimate, 0.05 * fit.sigma)

    # Each search starts from the others' optimum at the nearest value profiled so far
    # (the estimate at first): a few evaluations instead of a search from afar.
    solved: list[list[tuple[float, np.ndarray]]] = [[(estimate[j], estimate)] for j in range(k + 1)]

    def profiled(j: int, value: float) -> float:
        others = np.delete(np.arange(k + 1), j)
        nearest = min(solved[j], key=lambda pair: abs(pair[0] - value))[1]

        def rest(x):
            psi = estimate.copy()
            psi[j], psi[others] = value, x
            return deviance(psi)

        found = optimize.minimize(
            rest, [nearest[others]], lower[others], upper[others], step[others], xtol=1e-7
        )
        psi = estimate.copy()
        psi[j], psi[others] = value, found.x
        solved[j].append((value, psi))
        return found.fun - minimum - CUTOFF

    intervals: list[tuple[float, float] | None] = []
    for j in range(k + 1):
        floor = lower[j]
        if profiled(j, floor) < 0:
            low = float(floor) if j < k else float("nan")
        else:
            low = scipy_optimize.brentq(
                lambda c, j=j: profiled(j, c), floor, estimate[j], xtol=1e-7
            )
        high = estimate[j] + step[j]
        while profiled(j, high) < 0:
            high = estimate[j] + 2 * (high - estimate[j])
        top = scipy_optimize.brentq(lambda c, j=j: profiled(j, c), estimate[j], high, xtol=1e-7)
        intervals.append((float(low), float(top)))
    return intervals
