"""Fit a generalized linear mixed model by the Laplace approximation (maximum likelihood).

The model: η = Xβ + Z S v with v ~ N(0, I) and S = diag(σ) holding one standard
deviation per variance component (columns of Z that share a variance), and an
observation's log-likelihood given η from a family of :mod:`analysis.mixed.families`.
This is the formulation of Bates et al. (2015), "Fitting linear mixed-effects models
using lme4", J. Stat. Softw. 67(1) §3 and of ``glmer(nAGQ = 1)``/``clmm``: the random
effects' conditional mode v̂ is found by Newton's method, and the marginal log-likelihood
is approximated by

    ℓ_L(β, σ, ψ) = Σ ℓ_i(η̂_i) − ½ v̂ᵀv̂ − ½ log det(I + S Zᵀ W Z S),   W = −∂²ℓ/∂η²,

which is exact for a Gaussian response. As in ``glmer``, the fit has two stages: first β
joins v in the Newton steps and only σ and the family's extra parameters ψ are searched
(``nAGQ = 0``), then all of β, ψ and σ are searched on ℓ_L itself. Standard errors come
from the numerical Hessian of ℓ_L over (β, ψ, σ), like ``glmer``'s default ``vcov``
(central differences, one step for all parameters). glmer's own standard errors differ
from these by 0.1–1.3 % with its default ``tolPwrss = 1e-7``: its PIRLS stops on a
relative change in the penalized deviance and takes log det L from the iterate before
the last, so the deviance it differentiates lags the Laplace approximation; with
``glmerControl(tolPwrss = 1e-13)`` glmer gives these to 1e-5 (tests/analysis/
test_mixed_reference.py, reference/glmer_converged.R).
statsmodels has no maximum-likelihood fit of crossed random effects for binary or
ordinal responses (its mixed GLMs are variational Bayes), hence this module.
"""

import dataclasses
import itertools

import numpy as np
from scipy import linalg
from statsmodels.tools.numdiff import approx_hess3

from analysis.mixed import convergence, optimize
from analysis.mixed.degenerate import dropped_message, full_rank
from analysis.mixed.modes import ConditionalModes
from analysis.mixed.problem import (
    BOUNDARY_SD,
    LARGEST_SD,
    NEWTON_STEP,
    Component,
    LaplaceFit,
    MixedProblem,
)

# Starting SDs of the search on the logit scale: the optimum is kept of both.
SD_STARTS = (1.0, 0.3)
# The Hessian's finite-difference step, the same for every parameter (lme4's deriv12 takes
# 1e-4 for all). A step relative to each value, statsmodels' default, shrank to 1e-5 for
# an SD of 0.1, where the modes' 1e-10 convergence noise, divided by the step squared, moved
# standard errors by up to 0.5 % (issue 56, crossed set 56); from 2e-4 to 2e-3 they agree
# with glmer's to 1e-5.
HESSIAN_STEP = 5e-4

__all__ = ["BOUNDARY_SD", "LARGEST_SD", "Component", "LaplaceFit", "MixedProblem", "fit_laplace"]


def _start_beta(problem: MixedProblem, extra: np.ndarray) -> np.ndarray:
    """Fit the fixed effects alone (no random effects) by Newton's method."""
    family, y, X = problem.family, np.asarray(problem.y, float), np.asarray(problem.X, float)
    beta = np.zeros(X.shape[1])
    for _ in range(50):
        derivs = family.derivatives(X @ beta, y, extra)
        hessian = X.T @ (X * derivs.weight[:, None]) + 1e-8 * np.eye(len(beta))
        step = np.linalg.solve(hessian, X.T @ derivs.gradient)
        beta = beta + step
        if np.max(np.abs(step), initial=0.0) < NEWTON_STEP:
            break
    return beta


def fit_laplace(
    problem: MixedProblem,
    *,
    stage: str = "laplace",
    sd_start: float | np.ndarray | None = None,
    extra_start: np.ndarray | None = None,
) -> LaplaceFit:
    """Fit *problem* by maximum likelihood; ``stage="fast"`` stops after glmer's nAGQ = 0.

    *sd_start* (one value, or one per component) and *extra_start* (the family's extra
    parameters, natural scale) start the search; simulations pass the true values.
    Without *sd_start* the search starts from SDs of 1 and of 0.3 (logit scale) and
    keeps the better; both stages are BOBYQA with the bound test of
    :mod:`analysis.mixed.optimize`.
    """
    if stage not in ("laplace", "fast"):
        raise ValueError(f"stage must be 'laplace' or 'fast', not {stage!r}")
    problem, dropped = full_rank(problem)
    fit = _fit(problem, stage, sd_start, extra_start)
    if not dropped:
        return fit
    message = dropped_message(dropped)
    return dataclasses.replace(fit, dropped=dropped, checks=(message, *fit.checks))


def _fit(problem, stage, sd_start, extra_start) -> LaplaceFit:
    """Fit a problem with a full-rank fixed-effect design (fit_laplace's search)."""
    family = problem.family
    state = ConditionalModes(problem)
    extra_free = (
        family.extra_start(state.y) if extra_start is None else family.extra_free(extra_start)
    )
    first, beta, fast_loglik = _profiled_search(problem, state, sd_start, extra_free)
    k = len(problem.components)
    sd, extra_free = first.x[:k], first.x[k:]
    if stage == "fast":
        return _fast_fit(problem, state, sd, extra_free, beta, first, fast_loglik)
    return _laplace_fit(problem, state, sd, extra_free, beta)


def _profiled_search(problem, state, sd_start, extra_free):
    """Search the SDs (and a family's extra parameters) with β profiled out; return the
    optimiser's result, β at its optimum and the log-likelihood there."""
    family, k, n_extra = problem.family, len(problem.components), len(extra_free)
    memo = {"beta": _start_beta(problem, family.extra_natural(extra_free))}

    def objective(vector: np.ndarray) -> float:
        sd, free = vector[:k], vector[k:]
        value, found = state.profiled_loglik(
            sd[state.owner], family.extra_natural(free), memo["beta"]
        )
        if np.all(np.isfinite(found)):
            memo["beta"] = found
        return -2 * value if np.isfinite(value) else np.inf

    sd_starts = SD_STARTS if sd_start is None else (sd_start,)
    starts = [
        np.concatenate([np.broadcast_to(np.asarray(s, float), (k,)), extra_free]) for s in sd_starts
    ]
    lower = np.concatenate([np.zeros(k), np.full(n_extra, -np.inf)])
    upper = np.concatenate([np.full(k, LARGEST_SD), np.full(n_extra, np.inf)])
    step = np.concatenate([np.full(k, 0.2), np.full(n_extra, 0.2)])
    # The first stage only needs to land near the optimum: the second refines it, and
    # power simulations, which stop here, need no more than a few digits.
    first = optimize.minimize(objective, starts, lower, upper, step, xtol=1e-6)
    # Evaluating at the optimum leaves β and v there (the search's last call need not be).
    loglik = -objective(first.x) / 2
    return first, memo["beta"], loglik


def _fast_fit(problem, state, sd, extra_free, beta, first, loglik) -> LaplaceFit:
    """Finish the first stage's fit (lme4's nAGQ = 0): β's covariance at the joint mode."""
    family, p, n_extra = problem.family, state.p, len(extra_free)
    converged, message = first.converged, first.message
    beta, _, _, solve = state.joint_mode(sd[state.owner], family.extra_natural(extra_free), beta)
    try:
        unit = np.zeros((p + state.q, p))
        unit[np.arange(p), np.arange(p)] = 1.0
        cov = solve(unit)[:p, :p]
    except (np.linalg.LinAlgError, RuntimeError):
        cov = np.full((p, p), np.nan)
        converged, message = False, "singular Hessian: standard errors unavailable"
    params, names = beta, problem.fixed_names
    if n_extra:
        # The fast stage serves power simulations, which test β only.
        params = np.concatenate([beta, family.extra_natural(extra_free)])
        cov = linalg.block_diag(cov, np.full((n_extra, n_extra), np.nan))
        names = names + family.extra_names(state.y)
    return finish_fit(problem, state, names, params, cov, sd, converged, "fast", message, loglik)


def _laplace_fit(problem, state, sd, extra_free, beta) -> LaplaceFit:
    """Refine the first stage's estimates on the Laplace likelihood of all parameters;
    the covariance from its Hessian (lme4's nAGQ = 1)."""
    family, p, k, n_extra = problem.family, state.p, len(sd), len(extra_free)

    def objective(vector: np.ndarray) -> float:
        beta_, free, sd_ = vector[:p], vector[p : p + n_extra], vector[p + n_extra :]
        value = state.loglik(beta_, family.extra_natural(free), sd_)
        return -2 * value if np.isfinite(value) else np.inf

    start = np.concatenate([beta, extra_free, sd])
    lower = np.concatenate([np.full(p + n_extra, -np.inf), np.zeros(k)])
    upper = np.concatenate([np.full(p + n_extra, np.inf), np.full(k, LARGEST_SD)])
    step = np.concatenate([np.full(p + n_extra, 0.05), np.maximum(0.05, 0.1 * sd)])
    second = optimize.minimize(objective, [start], lower, upper, step)
    beta, extra_free, sd = second.x[:p], second.x[p : p + n_extra], second.x[p + n_extra :]
    extra = family.extra_natural(extra_free)
    converged, message = second.converged, second.message

    # Covariance from the Hessian of ℓ_L in natural parameters; a component fitted at
    # zero is held there (its likelihood is not smooth across the boundary).
    free_sd = sd > BOUNDARY_SD
    natural = np.concatenate([beta, extra, sd[free_sd]])

    def negative(vector: np.ndarray) -> float:
        sd_ = sd.copy()
        sd_[free_sd] = vector[p + n_extra :]
        return -state.loglik(vector[:p], vector[p : p + n_extra], sd_)

    hessian = approx_hess3(natural, negative, epsilon=HESSIAN_STEP)
    checks = convergence.check(
        lambda vector: 2 * negative(vector), natural, np.ones(len(natural), bool), 2 * hessian
    )
    try:
        cov = np.linalg.inv(hessian)[: p + n_extra, : p + n_extra]
    except np.linalg.LinAlgError:
        cov = np.full((p + n_extra, p + n_extra), np.nan)
        converged, message = False, "singular Hessian: standard errors unavailable"
    # Evaluating at the optimum leaves v̂ there (the Hessian's last call was elsewhere).
    loglik = state.loglik(beta, extra, sd)
    names = problem.fixed_names + family.extra_names(state.y)
    params = np.concatenate([beta, extra])
    fit = finish_fit(problem, state, names, params, cov, sd, converged, "laplace", message, loglik)
    return dataclasses.replace(fit, converged=converged and checks.ok, checks=checks.messages)


def finish_fit(
    problem, state, names, params, cov, sd, converged, stage, message, loglik
) -> LaplaceFit:
    """Collect a fit, with the random effects' modes (on η's scale) from ``state.v``."""
    u = (np.asarray(sd)[state.owner] * state.v)[state.position]
    bounds = np.cumsum([0] + [c.width for c in problem.components])
    modes = [u[start:end] for start, end in itertools.pairwise(bounds)]
    return LaplaceFit(
        names=tuple(names),
        params=np.asarray(params, dtype=float),
        cov=np.asarray(cov, dtype=float),
        sd=np.asarray(sd, dtype=float),
        loglik=float(loglik),
        nobs=len(state.y),
        converged=converged,
        evaluations=state.evaluations,
        stage=stage,
        modes=tuple(modes),
        message=message,
        singular=bool(np.any(np.asarray(sd) < BOUNDARY_SD)),
    )
