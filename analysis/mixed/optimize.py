"""Minimise a mixed model's criterion over parameters some of which are bounded at zero.

A variance parameter (an SD, or lme4's relative factor θ) enters the likelihood through
its square, so the criterion is flat to first order at θ = 0: a gradient method that
steps onto the bound finds a zero projected gradient there and stops, whether or not a
positive θ is better (issue 34). The search here is the one lme4 uses instead:

- BOBYQA (Powell 2009, "The BOBYQA algorithm for bound constrained optimization without
  derivatives"; nlopt's ``LN_BOBYQA``, lme4's default for ``lmer`` and ``glmer``'s first
  stage), which models the criterion by quadratic interpolation and needs no gradient;
- from several starts, the best kept;
- then every bounded parameter that ended on its bound is tested by a short profile
  (the criterion at small positive values, the others held): if one is lower, the
  search restarts from it, as lme4's ``restart_edge`` does for linear mixed models.
"""

import dataclasses
from collections.abc import Callable, Sequence

import numpy as np

from analysis.mixed.problem import BOUNDARY_SD

# A bounded parameter this close to its bound is on it (lme4's isSingular tolerance).
ON_BOUND = BOUNDARY_SD
# The short profile's trial values, as multiples of the parameter's initial step.
PROFILE = (1e-3, 1e-2, 0.1, 0.3, 1.0, 3.0)
RESTARTS = 5
# Returned to BOBYQA for an infeasible point (a factorisation that failed): large and
# finite, since interpolating an infinite value would poison its quadratic model.
INFEASIBLE = 1e100


@dataclasses.dataclass(frozen=True)
class Optimum:
    """The minimum found: ``x``, ``fun`` = criterion(x), and how BOBYQA ended."""

    x: np.ndarray
    fun: float
    converged: bool
    message: str


def _bobyqa(criterion, start, lower, upper, step, xtol, maxeval):
    import nlopt

    optimiser = nlopt.opt(nlopt.LN_BOBYQA, len(start))
    optimiser.set_lower_bounds(lower)
    optimiser.set_upper_bounds(upper)
    optimiser.set_initial_step(step)
    optimiser.set_xtol_abs(xtol)
    optimiser.set_ftol_abs(1e-13)
    optimiser.set_maxeval(maxeval)

    def wrapped(x, grad):
        value = criterion(np.asarray(x))
        return float(value) if np.isfinite(value) else INFEASIBLE

    optimiser.set_min_objective(wrapped)
    try:
        x = optimiser.optimize(np.clip(start, lower, upper))
    except nlopt.RoundoffLimited:
        return None
    result = optimiser.last_optimize_result()
    converged = result in (nlopt.FTOL_REACHED, nlopt.XTOL_REACHED, nlopt.SUCCESS)
    names = {nlopt.FTOL_REACHED: "ftol reached", nlopt.XTOL_REACHED: "xtol reached"}
    message = names.get(result, f"nlopt result {result}")
    return np.asarray(x), float(optimiser.last_optimum_value()), converged, message


def minimize(
    criterion: Callable[[np.ndarray], float],
    starts: Sequence[np.ndarray],
    lower: np.ndarray,
    upper: np.ndarray,
    step: np.ndarray,
    *,
    xtol: float = 1e-9,
    maxeval: int = 20000,
) -> Optimum:
    """Minimise *criterion* within [lower, upper] from each start; keep the best (module doc).

    Parameters whose lower bound is finite are the ones tested on their bound; *step* is
    BOBYQA's initial step per parameter and the scale of the short profile.
    """
    lower, upper = np.asarray(lower, float), np.asarray(upper, float)
    step = np.asarray(step, float)
    bounded = np.flatnonzero(np.isfinite(lower))
    best = None
    for start in starts:
        found = _bobyqa(criterion, np.asarray(start, float), lower, upper, step, xtol, maxeval)
        if found is not None and (best is None or found[1] < best[1]):
            best = found
    if best is None:
        raise ArithmeticError("the optimiser could not evaluate the criterion at any start")
    x, fun, converged, message = best
    for _ in range(RESTARTS):
        better = _off_the_bound(criterion, x, fun, lower, upper, step, bounded)
        if better is None:
            break
        found = _bobyqa(criterion, better[0], lower, upper, step, xtol, maxeval)
        if found is None or found[1] >= better[1]:
            x, fun = better
            continue
        x, fun, converged, message = found
    x, fun = _onto_the_bound(criterion, x, fun, lower, bounded)
    return Optimum(x, fun, converged, message)


def _onto_the_bound(criterion, x, fun, lower, bounded):
    """Put parameters within ON_BOUND of their bound onto it where that costs nothing.

    BOBYQA stops a few ulps of its trust region away from a bound; the criterion is flat
    there, and a report should say 0, as lme4 does, not 8.9e-09.
    """
    near = [j for j in bounded if 0 < x[j] - lower[j] < ON_BOUND]
    if not near:
        return x, fun
    snapped = x.copy()
    snapped[near] = lower[near]
    value = criterion(snapped)
    if value <= fun + 1e-9 * max(1.0, abs(fun)):
        return snapped, value
    return x, fun


def _off_the_bound(criterion, x, fun, lower, upper, step, bounded):
    """Return (point, value) with a bounded parameter moved off its bound that lowers
    *fun*, or None."""
    best, best_value = None, fun - 1e-10 * max(1.0, abs(fun))
    for j in bounded:
        if x[j] - lower[j] > ON_BOUND:
            continue
        for multiple in PROFILE:
            trial = x.copy()
            trial[j] = min(lower[j] + multiple * step[j], upper[j])
            value = criterion(trial)
            if value < best_value:
                best, best_value = trial, value
    return None if best is None else (best, best_value)
