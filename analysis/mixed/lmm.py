"""Fit a linear mixed model by REML or maximum likelihood with lme4's profiled criterion.

y = Xβ + ZΛu + ε, u ~ N(0, σ²I), ε ~ N(0, σ²I). Λ is block diagonal in lme4's relative
covariance factors θ: θ_k I for a component whose columns share one SD, a lower
triangular T_k (θ its entries, column by column) for a correlated one, so that a level's
effects have covariance σ² T_k T_kᵀ. For given θ, β and u solve the penalised least
squares problem min ‖y − Xβ − ZΛu‖² + ‖u‖² and, with A = ΛᵀZᵀZΛ + I,
R = XᵀX − XᵀZΛ A⁻¹ ΛᵀZᵀX and r² the penalised residual sum of squares,

    ML:   d(θ, σ) = log det A + n log(2πσ²) + r²/σ²,
    REML: d(θ, σ) = log det A + log det R + (n − p) log(2πσ²) + r²/σ²,

profiled over σ at σ² = r²/n or r²/(n − p) (Bates et al. 2015, J. Stat. Softw. 67(1)
§3.4–3.6, eqs. 34 and 41; the criteria of ``lmer``). Only θ is searched, by BOBYQA with
the bound test of :mod:`analysis.mixed.optimize`; cov(β̂) = σ² R⁻¹. As in lme4, A is
factored sparse in one symbolic analysis for every θ (analysis.mixed.cholesky), or with
one grouping factor's levels eliminated first where the rest is narrow. statsmodels'
MixedLM gives the same numbers but forms dense per-group matrices: ten minutes for
48,000 ratings by 1,000 participants, against seconds here; InstEval's 300 students ×
999 lecturers take seconds too (bench/bench_insteval.py).
"""

import dataclasses

import numpy as np

from analysis.mixed import convergence, optimize
from analysis.mixed.degenerate import dropped_message, full_rank
from analysis.mixed.factor import Factor
from analysis.mixed.modes import ConditionalModes
from analysis.mixed.problem import LARGEST_SD, MixedProblem
from analysis.mixed.relative import RelativeCross


@dataclasses.dataclass(frozen=True, eq=False)
class LinearFit:
    """A linear mixed model's estimates; ``criterion`` can re-evaluate it (tests, df, CIs).

    ``sd`` and ``columns`` hold one SD per random-effect column (component name and
    column), ``correlations`` each correlated pair (name, column a, column b, r).
    """

    names: tuple[str, ...]
    beta: np.ndarray
    cov: np.ndarray
    theta: np.ndarray
    sigma: float
    sd: np.ndarray
    columns: tuple[tuple[str, str], ...]
    correlations: tuple[tuple[str, str, str, float], ...]
    loglik: float
    reml: bool
    nobs: int
    converged: bool
    singular: bool
    checks: tuple[str, ...]
    message: str
    evaluations: int
    criterion: "LinearCriterion"
    dropped: tuple[str, ...] = ()
    # The components with a variance parameter on its bound (the fit is singular).
    singular_components: tuple[str, ...] = ()


def _lower_triangle(c: int) -> tuple[np.ndarray, np.ndarray]:
    """Return a c × c lower triangle's (rows, columns), column by column (lme4's θ order)."""
    rows, cols = np.tril_indices(c)
    order = np.lexsort((rows, cols))
    return rows[order], cols[order]


@dataclasses.dataclass(frozen=True)
class _Solution:
    logdet_a: float
    reduced: np.ndarray
    beta: np.ndarray
    u: np.ndarray
    r2: float


class LinearCriterion:
    """The deviance of one linear mixed model as a function of θ (and σ)."""

    def __init__(self, problem: MixedProblem, *, reml: bool = True):
        self.problem, self.reml = problem, reml
        self.state = ConditionalModes(problem)
        self.y, self.X = self.state.y, self.state.X
        self.n, self.p = self.X.shape
        self.xx, self.xy = self.X.T @ self.X, self.X.T @ self.y
        self.spans, lower, offset = [], [], 0
        for component in problem.components:
            c = len(component.columns)
            size = c * (c + 1) // 2 if component.correlated else 1
            self.spans.append((offset, offset + c, size, component.correlated))
            if component.correlated:
                rows, cols = _lower_triangle(c)
                lower += list(np.where(rows == cols, 0.0, -np.inf))
            else:
                lower.append(0.0)
            offset += c
        self.lower = np.array(lower)
        # Without correlated components Λ = diag(θ per column): ZᵀZ, Zᵀ X and Zᵀ y are
        # formed once and scaled, so an evaluation never touches the n rows again. With
        # them, ΛᵀZᵀZΛ + I is formed in ZᵀZ's fixed sparse pattern from sums kept per
        # stored entry (analysis.mixed.relative), and factored sparse.
        self.scaled = not any(c.correlated for c in problem.components)
        self.q = self.state.q
        self.zx, self.zy = self.state.z_t_dot(self.X), self.state.z_t_dot(self.y)
        self.yy = float(self.y @ self.y)
        if self.scaled:
            self.cross = self.state.scaled_cross(np.ones(self.n))
        else:
            self.relative = RelativeCross(self.state)

    def start(self, scale: float) -> np.ndarray:
        """Return θ with every SD *scale* times σ and no correlation."""
        return np.where(np.isfinite(self.lower), scale, 0.0)

    def factors(self, theta: np.ndarray) -> list[np.ndarray]:
        """Return each component's relative factor T (c × c lower triangular)."""
        out, at = [], 0
        for first, last, size, correlated in self.spans:
            c = last - first
            if correlated:
                block = np.zeros((c, c))
                block[_lower_triangle(c)] = theta[at : at + size]
            else:
                block = theta[at] * np.eye(c)
            out.append(block)
            at += size
        return out

    def solve(self, theta: np.ndarray) -> _Solution:
        """Solve the penalised least squares problem at θ."""
        theta = np.asarray(theta, float)
        if self.scaled:
            scale = theta[self.state.owner]
            factor = self.cross.factor(scale)
            return self._finish(factor, scale[:, None] * self.zx, scale * self.zy)
        factors = self.factors(theta)
        pattern, relative = self.state.pattern, self.relative
        factor = pattern.factor(relative.identity_plus(factors))
        zx, zy = (
            relative.transposed_times(factors, self.zx),
            relative.transposed_times(factors, self.zy),
        )
        return self._finish(factor, zx, zy)

    def _finish(self, factor: Factor, zx: np.ndarray, zy: np.ndarray) -> _Solution:
        """Solve for β and u given A's factor, ΛᵀZᵀX and ΛᵀZᵀy."""
        a_zx, a_zy = factor.solve(zx), factor.solve(zy)
        reduced = self.xx - zx.T @ a_zx
        beta = np.linalg.solve(reduced, self.xy - zx.T @ a_zy)
        u = a_zy - a_zx @ beta
        # At the solution the penalised residual sum of squares is yᵀy − b̂ᵀWᵀy,
        # W = [X, ZΛ]: no pass over the n rows.
        r2 = self.yy - float(beta @ self.xy) - float(u @ zy)
        return _Solution(factor.logdet, reduced, beta, u, r2)

    def _residual_df(self) -> int:
        return self.n - self.p if self.reml else self.n

    def profiled(self, theta: np.ndarray) -> float:
        """Return the deviance at θ with σ profiled out (lme4's devfun)."""
        self.state.evaluations += 1
        try:
            found = self.solve(theta)
        except (np.linalg.LinAlgError, RuntimeError):
            return np.inf
        sign, logdet_r = np.linalg.slogdet(found.reduced)
        if sign <= 0 or found.r2 <= 0:
            return np.inf
        m = self._residual_df()
        value = found.logdet_a + m * (1 + np.log(2 * np.pi * found.r2 / m))
        return value + (logdet_r if self.reml else 0.0)

    def deviance(self, varpar: np.ndarray) -> float:
        """Return the deviance at (θ, σ), σ last (lmerTest's ``devfun_vp``)."""
        theta, sigma = np.asarray(varpar[:-1], float), float(varpar[-1])
        try:
            found = self.solve(theta)
        except (np.linalg.LinAlgError, RuntimeError):
            return np.inf
        value = found.logdet_a + self._residual_df() * np.log(2 * np.pi * sigma**2)
        value += found.r2 / sigma**2
        if self.reml:
            value += np.linalg.slogdet(found.reduced)[1]
        return float(value)

    def covbeta(self, varpar: np.ndarray) -> np.ndarray:
        """Return cov(β̂) = σ² R⁻¹ at (θ, σ), σ last (lmerTest's ``get_covbeta``)."""
        found = self.solve(np.asarray(varpar[:-1], float))
        return float(varpar[-1]) ** 2 * np.linalg.inv(found.reduced)


def _random_effects(problem: MixedProblem, factors, sigma2: float):
    """Return the random effects' SDs, their (component, column) names, and the
    correlations within each correlated component, from the relative factors Λ."""
    sd, columns, correlations = [], [], []
    for component, block in zip(problem.components, factors, strict=True):
        covariance = sigma2 * block @ block.T
        spread = np.sqrt(np.diag(covariance))
        sd += list(spread)
        columns += [(component.name, column) for column in component.columns]
        if component.correlated:
            for i in range(len(spread)):
                for j in range(i):
                    r = covariance[i, j] / (spread[i] * spread[j]) if spread[i] * spread[j] else 0
                    a, b = component.columns[j], component.columns[i]
                    correlations.append((component.name, a, b, float(r)))
    return sd, columns, correlations


def fit_lmm(problem: MixedProblem, *, reml: bool = True) -> LinearFit:
    """Fit *problem* (its family is ignored: the response is Gaussian) by REML or ML.

    Fixed-effect columns that repeat others are dropped and named in ``dropped`` and
    ``checks`` (lme4's message).
    """
    problem, dropped = full_rank(problem)
    criterion = LinearCriterion(problem, reml=reml)
    lower = criterion.lower
    upper = np.full(len(lower), LARGEST_SD)
    search = optimize.minimize(
        criterion.profiled,
        [criterion.start(1.0), criterion.start(0.3)],
        lower,
        upper,
        np.full(len(lower), 0.2),
        xtol=1e-10,
    )
    theta = search.x
    found = criterion.solve(theta)
    sigma2 = found.r2 / criterion._residual_df()
    bounded = np.isfinite(lower)
    on_bound = bounded & (theta < optimize.ON_BOUND)
    sizes = [size for _, _, size, _ in criterion.spans]
    owners = np.repeat(np.arange(len(sizes)), sizes)
    singular_components = tuple(
        problem.components[k].name for k in sorted(set(owners[on_bound].tolist()))
    )
    checks = convergence.check(criterion.profiled, theta, ~on_bound)
    sd, columns, correlations = _random_effects(problem, criterion.factors(theta), sigma2)
    return LinearFit(
        names=tuple(problem.fixed_names),
        beta=found.beta,
        cov=sigma2 * np.linalg.inv(found.reduced),
        theta=theta,
        sigma=float(np.sqrt(sigma2)),
        sd=np.array(sd),
        columns=tuple(columns),
        correlations=tuple(correlations),
        loglik=-float(search.fun) / 2,
        reml=reml,
        nobs=criterion.n,
        converged=search.converged and checks.ok,
        singular=bool(singular_components),
        checks=((dropped_message(dropped),) if dropped else ()) + checks.messages,
        message=search.message,
        evaluations=criterion.state.evaluations,
        criterion=criterion,
        dropped=dropped,
        singular_components=singular_components,
    )
