"""The random effects' conditional modes of a mixed model and what the fits need of them.

Z is kept row-wise (each observation's few non-zero columns and values), so Zᵀ w and
Zᵀ W Z are bincounts. I + S Zᵀ W Z S is factored in blocks (analysis.mixed.factor) when
one grouping factor's levels can be eliminated first and what remains is narrow (items
rated by every participant), and otherwise as a sparse matrix of one fixed pattern,
refactored numerically at each θ and W (analysis.mixed.cholesky; crossed designs).
"""

import numpy as np
from scipy import linalg

from analysis.mixed.cholesky import SparsePattern
from analysis.mixed.factor import BLOCKED_UP_TO, Blocks, Factor
from analysis.mixed.problem import NEWTON_STEP, MixedProblem


def _grouped_with_first(components) -> list[int]:
    """Return the components grouped by the first one's factor (its intercepts, and e.g.
    participants' own strengths): each observation has one level of them, so their part
    of ZᵀWZ is block diagonal and Factor eliminates it first."""
    first = components[0] if components else None
    if first is None or first.correlated:
        return []
    return [
        k
        for k, c in enumerate(components)
        if not c.correlated
        and len(c.levels) == len(first.levels)
        and np.array_equal(c.codes, first.codes)
    ]


def _positions(components, grouped, order, widths, offsets, q: int) -> tuple[np.ndarray, int]:
    """Return each column of Z's place in Factor's order (the grouped components first,
    level by level) and the grouped columns per level."""
    per_level = [components[k].values.shape[1] for k in grouped]
    c = int(sum(per_level))
    position = np.empty(q, dtype=np.int64)
    inside = np.concatenate([[0], np.cumsum(per_level)])
    for at, k in enumerate(grouped):
        level, column = np.divmod(np.arange(widths[k]), per_level[at])
        position[offsets[k] : offsets[k + 1]] = level * c + inside[at] + column
    after = c * (len(components[0].levels) if components else 0)
    for k in order[len(grouped) :]:
        position[offsets[k] : offsets[k + 1]] = after + np.arange(widths[k])
        after += widths[k]
    return position, c


def _rows_of_z(components, order, position, offsets, n: int) -> tuple[np.ndarray, np.ndarray]:
    """Return Z's few non-zeros per row: their columns (n_obs, m) and values, the grouped
    components' entries first."""
    cols = np.column_stack(
        [
            position[
                offsets[k]
                + components[k].codes[:, None] * components[k].values.shape[1]
                + np.arange(components[k].values.shape[1])
            ]
            for k in order
        ]
        or [np.zeros((n, 0), dtype=np.int64)]
    )
    vals = np.column_stack([components[k].values for k in order] or [np.zeros((n, 0))])
    return cols, vals


class ConditionalModes:
    """The approximate log-likelihood of one problem, with a warm start for v̂."""

    def __init__(self, problem: MixedProblem):
        self.problem = problem
        self.y = np.asarray(problem.y, dtype=float)
        self.X = np.asarray(problem.X, dtype=float)
        self.n, self.p = self.X.shape
        components = problem.components
        widths = [c.width for c in components]
        offsets = np.concatenate([[0], np.cumsum(widths)]).astype(np.int64)
        self.q = int(sum(widths))
        grouped = _grouped_with_first(components)
        order = grouped + [k for k in range(len(components)) if k not in grouped]
        self.position, c = _positions(components, grouped, order, widths, offsets, self.q)
        self.cols, self.vals = _rows_of_z(components, order, self.position, offsets, self.n)
        self.order = tuple(order)
        self.offsets = offsets
        self.owner = np.empty(self.q, dtype=np.int64)
        self.owner[self.position] = np.repeat(np.arange(len(widths)), widths)
        self.v = np.zeros(self.q)
        self.evaluations = 0
        self.head = c * len(components[0].levels) if grouped else 0
        self.rest_width = self.q - self.head
        self.level_width = c
        # I + S ZᵀWZ S is factored in blocks, the grouped levels eliminated first, when
        # the rest is narrow; otherwise sparse in one fixed pattern (crossed designs).
        self.blocked = bool(grouped) and self.rest_width <= BLOCKED_UP_TO
        # The joint Hessian's pattern and the slots of β's, the sides' and v's values.
        self._joint: tuple[SparsePattern, np.ndarray, np.ndarray, np.ndarray] | None = None
        self._index_pattern()
        if self.blocked:
            self._index_blocks(c)

    def _index_blocks(self, c: int) -> None:
        """Set the flat indices of each row's entries in the blocks Factor works on: the
        grouped levels' c × c pivots, their coupling to the rest, and the rest's square."""
        k, r = self.head, self.rest_width
        head, rest = self.cols[:, :c], self.cols[:, c:] - k
        level = head[:, 0] // c
        within = head - level[:, None] * c
        self.pivot_index = (
            level[:, None, None] * c * c + within[:, :, None] * c + within[:, None, :]
        ).ravel()
        self.coupling_index = (head[:, :, None] * r + rest[:, None, :]).ravel()
        self.rest_pairs = (rest[:, :, None] * r + rest[:, None, :]).ravel()

    def _index_pattern(self) -> None:
        """Set ZᵀZ's pattern (each row's pairs of columns) and each row's pairs' slots."""
        first, second = np.triu_indices(self.cols.shape[1])
        rows, cols = self.cols[:, first], self.cols[:, second]
        self.pattern = SparsePattern(rows, cols, self.q)
        self.pair_columns = (first, second)
        self.pair_slots = self.pattern.slots(rows, cols).ravel()

    def _pattern_values(self, weight: np.ndarray, vals: np.ndarray | None = None) -> np.ndarray:
        """Return Zᵀ W Z's values in :attr:`pattern`'s slots (Z's row values *vals*, or
        the problem's own)."""
        vals = self.vals if vals is None else vals
        first, second = self.pair_columns
        products = weight[:, None] * vals[:, first] * vals[:, second]
        return np.bincount(self.pair_slots, products.ravel(), minlength=len(self.pattern.keys))

    def z_dot(self, vector: np.ndarray) -> np.ndarray:
        """Return Z @ vector, shape (n_obs,)."""
        return (self.vals * vector[self.cols]).sum(axis=1)

    def z_t_dot(self, weights: np.ndarray, vals: np.ndarray | None = None) -> np.ndarray:
        """Return Zᵀ @ weights for weights (n_obs,) or (n_obs, k) (Z's row values *vals*,
        or the problem's own)."""
        vals = self.vals if vals is None else vals
        if weights.ndim == 1:
            return np.bincount(
                self.cols.ravel(), (vals * weights[:, None]).ravel(), minlength=self.q
            )
        return np.column_stack([self.z_t_dot(weights[:, j], vals) for j in range(weights.shape[1])])

    def _raw_blocks(self, weight: np.ndarray) -> Blocks:
        """Return Zᵀ W Z in blocks, unscaled and without I (needs the grouped components
        first): the grouped levels' part is (k,) when one column each, else (L, c, c)."""
        k, r, c = self.head, self.rest_width, self.level_width
        head_values, rest = self.vals[:, :c], self.vals[:, c:]
        weighted = weight[:, None] * head_values
        if c == 1:
            pivots = np.bincount(self.cols[:, 0], weighted[:, 0] * head_values[:, 0], minlength=k)
        else:
            products = weighted[:, :, None] * head_values[:, None, :]
            pivots = np.bincount(self.pivot_index, products.ravel(), minlength=k * c)
            pivots = pivots.reshape(k // c, c, c)
        coupling = np.bincount(
            self.coupling_index, (weighted[:, :, None] * rest[:, None, :]).ravel(), minlength=k * r
        ).reshape(k, r)
        products = weight[:, None, None] * rest[:, :, None] * rest[:, None, :]
        cross = np.bincount(self.rest_pairs, products.ravel(), minlength=r * r).reshape(r, r)
        return Blocks(pivots, coupling, cross)

    def _scale_blocks(self, raw: Blocks, scale: np.ndarray) -> Blocks:
        """Return I + S (raw) S in blocks, raw from :meth:`_raw_blocks`."""
        k, c = self.head, self.level_width
        head, tail = scale[:k], scale[k:]
        if c == 1:
            pivots = 1 + head**2 * raw.pivots
        else:
            shaped = head.reshape(-1, c)
            pivots = np.eye(c) + shaped[:, :, None] * raw.pivots * shaped[:, None, :]
        return Blocks(
            pivots,
            head[:, None] * raw.coupling * tail[None, :],
            np.eye(len(tail)) + tail[:, None] * raw.rest * tail[None, :],
        )

    def _blocks(self, weight: np.ndarray, scale: np.ndarray) -> Blocks:
        """Return I + S Zᵀ W Z S in blocks (needs the grouped components first)."""
        return self._scale_blocks(self._raw_blocks(weight), scale)

    def scaled_cross(self, weight: np.ndarray) -> "ScaledCross":
        """Return ZᵀWZ kept so that I + S ZᵀWZ S factors for any S without touching Z."""
        return ScaledCross(self, weight)

    def factor(self, weight: np.ndarray, scale: np.ndarray) -> Factor:
        """Factor I + S Zᵀ W Z S."""
        if self.blocked:
            return Factor(self._blocks(weight, scale))
        values = self.pattern.identity_plus_scaled(self._pattern_values(weight), scale)
        return self.pattern.factor(values)

    def mode(self, eta_fixed: np.ndarray, scale: np.ndarray, extra: np.ndarray):
        """Return (v̂, Σℓ_i, log det H) at the conditional mode of v (Newton with halving)."""
        family, y = self.problem.family, self.y

        def evaluate(vector):
            derivs = family.derivatives(eta_fixed + self.z_dot(scale * vector), y, extra)
            return derivs, derivs.loglik.sum() - 0.5 * vector @ vector

        def newton_step(vector, derivs):
            factor = self.factor(derivs.weight, scale)
            return factor.solve(scale * self.z_t_dot(derivs.gradient) - vector), factor

        v, derivs, factor = _newton(evaluate, newton_step, self.v)
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

        def evaluate(vector):
            eta = X @ vector[:p] + self.z_dot(scale * vector[p:])
            derivs = family.derivatives(eta, y, extra)
            return derivs, derivs.loglik.sum() - 0.5 * vector[p:] @ vector[p:]

        def newton_step(vector, derivs):
            g = derivs.gradient
            gradient = np.concatenate([X.T @ g, scale * self.z_t_dot(g) - vector[p:]])
            try:
                solve = self._joint_solver(scale, derivs.weight)
            except (linalg.LinAlgError, RuntimeError):
                dense = self._joint_hessian(scale, derivs.weight)

                def solve(rhs, dense=dense):
                    return linalg.lstsq(dense, rhs)[0]

            return solve(gradient), solve

        theta, derivs, solve = _newton(evaluate, newton_step, np.concatenate([beta, self.v]))
        return theta[:p], theta[p:], derivs, solve

    def _joint_solver(self, scale: np.ndarray, weight: np.ndarray):
        """Return a solver of the joint Hessian over (β, v), in that order."""
        if not self.blocked:
            return self._joint_pattern().factor(self._joint_values(scale, weight)).solve
        X, p, k = self.X, self.p, self.head
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

    def _joint_pattern(self) -> SparsePattern:
        """Return the joint Hessian's pattern over (β, v): β's rows dense, then ZᵀZ's."""
        return self._joint_layout()[0]

    def _joint_layout(self) -> tuple[SparsePattern, np.ndarray, np.ndarray, np.ndarray]:
        """Return the joint Hessian's pattern and the slots of β's, the sides' and v's
        values in it (made on first use)."""
        if self._joint is None:
            p, q = self.p, self.q
            beta_rows, beta_cols = np.triu_indices(p)
            side_rows, side_cols = np.repeat(np.arange(p), q), p + np.tile(np.arange(q), p)
            v_rows, v_cols = p + self.pattern.rows, p + self.pattern.cols
            pattern = SparsePattern(
                np.concatenate([beta_rows, side_rows, v_rows]),
                np.concatenate([beta_cols, side_cols, v_cols]),
                p + q,
            )
            self._joint = (
                pattern,
                pattern.slots(beta_rows, beta_cols),
                pattern.slots(side_rows, side_cols),
                pattern.slots(v_rows, v_cols),
            )
        return self._joint

    def _joint_values(self, scale: np.ndarray, weight: np.ndarray) -> np.ndarray:
        """Return the joint Hessian's values in :meth:`_joint_pattern`'s slots."""
        pattern, beta_slots, side_slots, v_slots = self._joint_layout()
        weighted = self.X * weight[:, None]
        values = np.zeros(len(pattern.keys))
        values[beta_slots] = (self.X.T @ weighted)[np.triu_indices(self.p)]
        values[side_slots] = (scale[:, None] * self.z_t_dot(weighted)).T.ravel()
        v_values = self._pattern_values(weight)
        values[v_slots] = self.pattern.identity_plus_scaled(v_values, scale)
        return values

    def _joint_hessian(self, scale: np.ndarray, weight: np.ndarray) -> np.ndarray:
        """Return the joint Hessian over (β, v), dense (a singular system's fallback)."""
        return self._joint_pattern().dense(self._joint_values(scale, weight))

    def profiled_loglik(self, scale: np.ndarray, extra: np.ndarray, beta: np.ndarray):
        """Return ℓ_L at the joint mode of (β, v) for given SDs (per column) and extras."""
        self.evaluations += 1
        beta, v, derivs, _ = self.joint_mode(scale, extra, beta)
        if np.all(np.isfinite(v)):
            self.v = v
        logdet = self.factor(derivs.weight, scale).logdet
        return float(derivs.loglik.sum() - 0.5 * v @ v - 0.5 * logdet), beta


class ScaledCross:
    """ZᵀWZ of one problem for a fixed W: factor I + S ZᵀWZ S for many S (one per θ)."""

    def __init__(self, modes: ConditionalModes, weight: np.ndarray):
        self.modes = modes
        # ZᵀWZ in the blocked layout, or as values in the sparse pattern's slots.
        self.raw: Blocks | np.ndarray = (
            modes._raw_blocks(weight) if modes.blocked else modes._pattern_values(weight)
        )

    def factor(self, scale: np.ndarray) -> Factor:
        """Factor I + S ZᵀWZ S for S = diag(*scale*)."""
        if isinstance(self.raw, Blocks):
            return Factor(self.modes._scale_blocks(self.raw, scale))
        pattern = self.modes.pattern
        return pattern.factor(pattern.identity_plus_scaled(self.raw, scale))


def _newton(evaluate, newton_step, start: np.ndarray):
    """Maximise a concave objective by Newton's method with step halving.

    ``evaluate(x)`` returns (derivatives, value); ``newton_step(x, derivatives)`` returns
    (step, what the step was solved with). Return x, its derivatives and the last solver,
    which is the one at x (the loop stops on a step too small to take).
    """
    x = start.copy()
    derivs, value = evaluate(x)
    for _ in range(100):
        step, solver = newton_step(x, derivs)
        if np.max(np.abs(step), initial=0.0) < NEWTON_STEP:
            break
        for _ in range(30):
            trial_derivs, trial_value = evaluate(x + step)
            if trial_value >= value - 1e-12 * abs(value):
                break
            step = step / 2
        x, derivs, value = x + step, trial_derivs, trial_value
    else:
        _, solver = newton_step(x, derivs)
    return x, derivs, solver
