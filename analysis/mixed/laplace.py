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
from the numerical Hessian of ℓ_L over (β, ψ, σ), like ``glmer``'s default ``vcov``.
statsmodels has no maximum-likelihood fit of crossed random effects for binary or
ordinal responses (its mixed GLMs are variational Bayes), hence this module.
"""

import dataclasses

import numpy as np
from scipy import linalg, optimize, sparse
from statsmodels.tools.numdiff import approx_hess3

from analysis.mixed.factor import DENSE_UP_TO, Blocks, Factor
from analysis.mixed.families import Bernoulli

# Newton stops when no step component exceeds this. The outer search differentiates
# the result numerically, so it must be smooth to far more digits than it reports
# (1e-7 here made the search wander and the fits miss lme4's by over 0.5 %).
NEWTON_STEP = 1e-10
# Below this SD a component is taken to sit on its boundary of zero (lme4 reports 0 too).
BOUNDARY_SD = 1e-4
# The search keeps SDs below this; on a logit scale larger ones mean certainty, and a
# flat likelihood out there only sends the optimiser wandering.
LARGEST_SD = 50.0


@dataclasses.dataclass(frozen=True, eq=False)
class Component:
    """A block of random-effect columns that share one standard deviation.

    Observation i has ``values[i]`` in the columns of level ``codes[i]`` of the grouping
    factor: ``codes`` (n_obs,), ``values`` (n_obs, len(columns)); the block is
    len(levels) × len(columns) wide (an intercept per level, or one slope per column).
    """

    name: str
    group: str
    levels: tuple[str, ...]
    columns: tuple[str, ...]
    codes: np.ndarray
    values: np.ndarray

    @property
    def width(self) -> int:
        return len(self.levels) * len(self.columns)

    @classmethod
    def from_codes(
        cls,
        name: str,
        group: str,
        codes: np.ndarray,
        levels: tuple[str, ...],
        values: np.ndarray | None = None,
        columns: tuple[str, ...] = ("(Intercept)",),
    ) -> "Component":
        """Build the component for level codes (n_obs,) and per-level values (n_obs, c)."""
        codes = np.asarray(codes, dtype=np.int64)
        values = np.ones((len(codes), 1)) if values is None else np.asarray(values, float)
        return cls(
            name, group, tuple(levels), tuple(columns), codes, values.reshape(len(codes), -1)
        )


@dataclasses.dataclass(frozen=True, eq=False)
class MixedProblem:
    """Response, fixed-effect design and variance components of one model.

    ``y`` (n_obs,), ``X`` (n_obs, p) with ``fixed_names``, and the family.
    """

    y: np.ndarray
    X: np.ndarray
    fixed_names: tuple[str, ...]
    components: tuple[Component, ...]
    family: object = Bernoulli()


@dataclasses.dataclass(frozen=True, eq=False)
class LaplaceFit:
    """The maximum-likelihood estimates of one mixed model and what they rest on.

    ``params`` are β then the family's extra parameters (natural scale), with
    covariance ``cov``; ``sd`` one standard deviation per component; ``modes`` the
    random effects' conditional modes (on the scale of η) per component.
    """

    names: tuple[str, ...]
    params: np.ndarray
    cov: np.ndarray
    sd: np.ndarray
    loglik: float
    nobs: int
    converged: bool
    evaluations: int
    stage: str
    modes: tuple[np.ndarray, ...]
    message: str = ""


class _Laplace:
    """The approximate log-likelihood of one problem, with a warm start for v̂."""

    def __init__(self, problem: MixedProblem):
        self.problem = problem
        self.y = np.asarray(problem.y, dtype=float)
        self.X = np.asarray(problem.X, dtype=float)
        self.n, self.p = self.X.shape
        widths = [c.width for c in problem.components]
        offsets = np.concatenate([[0], np.cumsum(widths)]).astype(np.int64)
        # Each row of Z has few non-zeros: its columns (n_obs, m) and their values.
        self.cols = np.column_stack(
            [
                offsets[k] + c.codes[:, None] * c.values.shape[1] + np.arange(c.values.shape[1])
                for k, c in enumerate(problem.components)
            ]
            or [np.zeros((self.n, 0), dtype=np.int64)]
        )
        self.vals = np.column_stack(
            [c.values for c in problem.components] or [np.zeros((self.n, 0))]
        )
        self.owner = np.repeat(np.arange(len(widths)), widths)
        self.q = int(sum(widths))
        self.pairs = (
            (self.cols[:, :, None] * self.q + self.cols[:, None, :]).ravel()
            if self.q <= DENSE_UP_TO
            else None
        )
        self.v = np.zeros(self.q)
        self.evaluations = 0
        # The first component's block of ZᵀWZ is diagonal when it is one intercept per
        # level (each observation in one level): Factor eliminates it first.
        first = problem.components[0] if problem.components else None
        self.diagonal = (
            np.arange(first.width)
            if first is not None and first.values.shape[1] == 1 and self.q <= DENSE_UP_TO
            else None
        )
        if self.diagonal is not None:
            k = first.width
            self.rest_width = self.q - k
            rest = self.cols[:, 1:] - k
            self.coupling_index = (self.cols[:, :1] * self.rest_width + rest).ravel()
            self.rest_pairs = (rest[:, :, None] * self.rest_width + rest[:, None, :]).ravel()

    def z_dot(self, vector: np.ndarray) -> np.ndarray:
        """Return Z @ vector, shape (n_obs,)."""
        return (self.vals * vector[self.cols]).sum(axis=1)

    def z_t_dot(self, weights: np.ndarray) -> np.ndarray:
        """Return Zᵀ @ weights for weights (n_obs,) or (n_obs, k)."""
        if weights.ndim == 1:
            return np.bincount(
                self.cols.ravel(), (self.vals * weights[:, None]).ravel(), minlength=self.q
            )
        return np.column_stack([self.z_t_dot(weights[:, j]) for j in range(weights.shape[1])])

    def _weighted_cross(self, weight: np.ndarray, scale: np.ndarray):
        """Return S Zᵀ W Z S, shape (q, q): dense, or sparse above DENSE_UP_TO columns."""
        products = weight[:, None, None] * self.vals[:, :, None] * self.vals[:, None, :]
        if self.q > DENSE_UP_TO:
            rows = np.repeat(self.cols, self.cols.shape[1], axis=1).ravel()
            cols = np.tile(self.cols, (1, self.cols.shape[1])).ravel()
            cross = sparse.csc_array((products.ravel(), (rows, cols)), shape=(self.q, self.q))
            diagonal = sparse.diags_array(scale)
            return diagonal @ cross @ diagonal
        cross = np.bincount(self.pairs, products.ravel(), minlength=self.q * self.q)
        cross = cross.reshape(self.q, self.q)
        return scale[:, None] * cross * scale[None, :]

    def _blocks(self, weight: np.ndarray, scale: np.ndarray) -> Blocks:
        """Return I + S Zᵀ W Z S in blocks (needs the diagonal first component)."""
        k, r = len(self.diagonal), self.rest_width
        first, rest = self.vals[:, 0], self.vals[:, 1:]
        head, tail = scale[:k], scale[k:]
        pivots = 1 + head**2 * np.bincount(self.cols[:, 0], weight * first**2, minlength=k)
        coupling = np.bincount(
            self.coupling_index, ((weight * first)[:, None] * rest).ravel(), minlength=k * r
        ).reshape(k, r)
        products = weight[:, None, None] * rest[:, :, None] * rest[:, None, :]
        cross = np.bincount(self.rest_pairs, products.ravel(), minlength=r * r).reshape(r, r)
        return Blocks(
            pivots,
            head[:, None] * coupling * tail[None, :],
            np.eye(r) + tail[:, None] * cross * tail[None, :],
        )

    def _factor(self, weight: np.ndarray, scale: np.ndarray) -> Factor:
        """Factor I + S Zᵀ W Z S."""
        if self.diagonal is not None:
            return Factor(self._blocks(weight, scale))
        return Factor(self._eye() + self._weighted_cross(weight, scale))

    def _eye(self):
        return sparse.eye_array(self.q, format="csc") if self.q > DENSE_UP_TO else np.eye(self.q)

    def mode(self, eta_fixed: np.ndarray, scale: np.ndarray, extra: np.ndarray):
        """Return (v̂, Σℓ_i, log det H) at the conditional mode of v (Newton with halving)."""
        family, y = self.problem.family, self.y
        v = self.v.copy()

        def objective(vector):
            eta = eta_fixed + self.z_dot(scale * vector)
            return family.derivatives(eta, y, extra), eta

        derivs, _ = objective(v)
        value = derivs.loglik.sum() - 0.5 * v @ v
        for _ in range(100):
            gradient = scale * self.z_t_dot(derivs.gradient) - v
            factor = self._factor(derivs.weight, scale)
            step = factor.solve(gradient)
            if np.max(np.abs(step), initial=0.0) < NEWTON_STEP:
                break
            for _ in range(30):
                trial_derivs, _ = objective(v + step)
                trial_value = trial_derivs.loglik.sum() - 0.5 * (v + step) @ (v + step)
                if trial_value >= value - 1e-12 * abs(value):
                    break
                step = step / 2
            v, derivs, value = v + step, trial_derivs, trial_value
        else:
            factor = self._factor(derivs.weight, scale)
        return v, float(derivs.loglik.sum()), factor.logdet

    def loglik(self, beta: np.ndarray, extra: np.ndarray, sd: np.ndarray) -> float:
        """Return ℓ_L at β, the family's natural extra parameters and the SDs."""
        self.evaluations += 1
        scale = np.asarray(sd, dtype=float)[self.owner]
        v, total, logdet = self.mode(self.X @ beta, scale, extra)
        if np.all(np.isfinite(v)):
            self.v = v
        return total - 0.5 * v @ v - 0.5 * logdet

    def joint_mode(self, scale: np.ndarray, extra: np.ndarray, beta: np.ndarray):
        """Maximise Σℓ_i − ½vᵀv over β and v together (glmer's nAGQ = 0 step)."""
        family, y, X, p = self.problem.family, self.y, self.X, self.p
        theta = np.concatenate([beta, self.v])

        def evaluate(vector):
            eta = X @ vector[:p] + self.z_dot(scale * vector[p:])
            derivs = family.derivatives(eta, y, extra)
            return derivs, derivs.loglik.sum() - 0.5 * vector[p:] @ vector[p:]

        derivs, value = evaluate(theta)
        for _ in range(100):
            g = derivs.gradient
            gradient = np.concatenate([X.T @ g, scale * self.z_t_dot(g) - theta[p:]])
            try:
                solve = self._joint_solver(scale, derivs.weight)
                step = solve(gradient)
            except (linalg.LinAlgError, RuntimeError):
                hessian = self._joint_hessian(scale, derivs.weight)
                dense = hessian.toarray() if sparse.issparse(hessian) else hessian
                step = linalg.lstsq(dense, gradient)[0]

                def solve(rhs, dense=dense):
                    return linalg.lstsq(dense, rhs)[0]

            if np.max(np.abs(step), initial=0.0) < NEWTON_STEP:
                break
            for _ in range(30):
                trial_derivs, trial_value = evaluate(theta + step)
                if trial_value >= value - 1e-12 * abs(value):
                    break
                step = step / 2
            theta, derivs, value = theta + step, trial_derivs, trial_value
        return theta[:p], theta[p:], derivs, solve

    def _joint_solver(self, scale: np.ndarray, weight: np.ndarray):
        """Return a solver of the joint Hessian over (β, v), in that order."""
        if self.diagonal is None:
            return Factor(self._joint_hessian(scale, weight)).solve
        X, p, k = self.X, self.p, len(self.diagonal)
        weighted = X * weight[:, None]
        side = scale[:, None] * self.z_t_dot(weighted)
        blocks = self._blocks(weight, scale)
        # Order (v of the first component, β, the other v): the diagonal block first.
        rest = np.block([[X.T @ weighted, side[k:].T], [side[k:], blocks.rest]])
        factor = Factor(Blocks(blocks.pivots, np.hstack([side[:k], blocks.coupling]), rest))
        order = np.concatenate([p + np.arange(k), np.arange(p), p + k + np.arange(self.q - k)])

        def solve(rhs: np.ndarray) -> np.ndarray:
            rhs = np.asarray(rhs, dtype=float)
            result = np.empty_like(rhs)
            result[order] = factor.solve(rhs[order])
            return result

        return solve

    def _joint_hessian(self, scale: np.ndarray, weight: np.ndarray) -> np.ndarray:
        X = self.X
        weighted = X * weight[:, None]
        top = X.T @ weighted
        side = scale[:, None] * self.z_t_dot(weighted)
        corner = self._weighted_cross(weight, scale) + self._eye()
        if sparse.issparse(corner):
            return sparse.block_array([[top, side.T], [side, corner]], format="csc")
        return np.block([[top, side.T], [side, corner]])

    def profiled_loglik(self, scale: np.ndarray, extra: np.ndarray, beta: np.ndarray):
        """Return ℓ_L at the joint mode of (β, v) for given SDs (per column) and extras."""
        self.evaluations += 1
        beta, v, derivs, _ = self.joint_mode(scale, extra, beta)
        if np.all(np.isfinite(v)):
            self.v = v
        logdet = self._factor(derivs.weight, scale).logdet
        return float(derivs.loglik.sum() - 0.5 * v @ v - 0.5 * logdet), beta


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
    sd_start: float | np.ndarray = 1.0,
    extra_start: np.ndarray | None = None,
) -> LaplaceFit:
    """Fit *problem* by maximum likelihood; ``stage="fast"`` stops after glmer's nAGQ = 0.

    *sd_start* (one value, or one per component) and *extra_start* (the family's extra
    parameters, natural scale) start the search; simulations pass the true values.
    """
    if stage not in ("laplace", "fast"):
        raise ValueError(f"stage must be 'laplace' or 'fast', not {stage!r}")
    family = problem.family
    state = _Laplace(problem)
    p, k = state.p, len(problem.components)
    extra_free = (
        family.extra_start(state.y) if extra_start is None else family.extra_free(extra_start)
    )
    n_extra = len(extra_free)
    beta = _start_beta(problem, family.extra_natural(extra_free))
    memo = {"beta": beta}

    def fast_objective(vector: np.ndarray) -> float:
        sd, free = vector[:k], vector[k:]
        value, found = state.profiled_loglik(
            sd[state.owner], family.extra_natural(free), memo["beta"]
        )
        if np.all(np.isfinite(found)):
            memo["beta"] = found
        return -2 * value if np.isfinite(value) else np.inf

    start = np.concatenate([np.broadcast_to(np.asarray(sd_start, float), (k,)), extra_free])
    bounds = [(0.0, LARGEST_SD)] * k + [(None, None)] * n_extra
    # The first stage only needs to land near the optimum: the second refines it, and
    # power simulations, which stop here, need no more than a few digits.
    first = optimize.minimize(
        fast_objective, start, method="L-BFGS-B", bounds=bounds, options={"ftol": 1e-7}
    )
    sd, extra_free = first.x[:k], first.x[k:]
    fast_objective(first.x)
    beta = memo["beta"]
    converged, message = bool(first.success), str(first.message)

    if stage == "fast":
        scale = sd[state.owner]
        beta, _, _, solve = state.joint_mode(scale, family.extra_natural(extra_free), beta)
        try:
            unit = np.zeros((p + state.q, p))
            unit[np.arange(p), np.arange(p)] = 1.0
            inverse = solve(unit)[:p, :p]
        except (np.linalg.LinAlgError, RuntimeError):
            inverse = np.full((p, p), np.nan)
            converged, message = False, "singular Hessian: standard errors unavailable"
        params = beta
        cov = inverse
        names = problem.fixed_names
        if n_extra:
            # The fast stage serves power simulations, which test β only.
            params = np.concatenate([beta, family.extra_natural(extra_free)])
            cov = linalg.block_diag(inverse, np.full((n_extra, n_extra), np.nan))
            names = names + family.extra_names(state.y)
        return _finish(problem, state, names, params, cov, sd, converged, "fast", message)

    def full_objective(vector: np.ndarray) -> float:
        beta_, free, sd_ = vector[:p], vector[p : p + n_extra], vector[p + n_extra :]
        value = state.loglik(beta_, family.extra_natural(free), sd_)
        return -2 * value if np.isfinite(value) else np.inf

    start = np.concatenate([beta, extra_free, sd])
    bounds = [(None, None)] * (p + n_extra) + [(0.0, LARGEST_SD)] * k
    second = optimize.minimize(
        full_objective, start, method="L-BFGS-B", bounds=bounds, options={"maxiter": 500}
    )
    beta, extra_free, sd = second.x[:p], second.x[p : p + n_extra], second.x[p + n_extra :]
    extra = family.extra_natural(extra_free)
    converged, message = bool(second.success), str(second.message)

    # Covariance from the Hessian of ℓ_L in natural parameters; a component fitted at
    # zero is held there (its likelihood is not smooth across the boundary).
    free_sd = sd > BOUNDARY_SD
    natural = np.concatenate([beta, extra, sd[free_sd]])

    def negative(vector: np.ndarray) -> float:
        sd_ = sd.copy()
        sd_[free_sd] = vector[p + n_extra :]
        return -state.loglik(vector[:p], vector[p : p + n_extra], sd_)

    hessian = approx_hess3(natural, negative)
    try:
        cov = np.linalg.inv(hessian)[: p + n_extra, : p + n_extra]
    except np.linalg.LinAlgError:
        cov = np.full((p + n_extra, p + n_extra), np.nan)
        converged, message = False, "singular Hessian: standard errors unavailable"
    state.loglik(beta, extra, sd)
    names = problem.fixed_names + family.extra_names(state.y)
    params = np.concatenate([beta, extra])
    return _finish(problem, state, names, params, cov, sd, converged, "laplace", message)


def _finish(problem, state, names, params, cov, sd, converged, stage, message) -> LaplaceFit:
    scale = np.asarray(sd)[state.owner]
    u = scale * state.v
    modes, start = [], 0
    for component in problem.components:
        width = component.width
        modes.append(u[start : start + width])
        start += width
    beta = params[: state.p]
    extra = params[state.p :]
    loglik = state.loglik(beta, extra, sd) if stage == "laplace" else np.nan
    if stage == "fast":
        loglik = state.profiled_loglik(scale, extra if len(extra) else np.zeros(0), beta)[0]
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
    )
