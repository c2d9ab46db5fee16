"""Factor the symmetric positive-definite matrices of a mixed model: solve and log det."""

import dataclasses

import numpy as np
from scipy import linalg

# A fit eliminates the first grouping factor's levels and factors the rest dense (Blocks)
# up to this many columns; wider ones are factored sparse in a fixed pattern
# (analysis.mixed.cholesky). Measured on fully crossed designs (every participant rates
# every item, the sparse path's worst case): at 100 items the blocks are 10–25 % faster,
# at 150 and more the sparse path is as fast with one BLAS thread and 10–30 times faster
# with two, where OpenBLAS's threads contend over the small dense matrices.
BLOCKED_UP_TO = 100


@dataclasses.dataclass(frozen=True)
class Blocks:
    """The symmetric matrix [[P, coupling], [couplingᵀ, rest]], kept in blocks.

    P is diag(pivots) for pivots of shape (k,), or block diagonal with L dense c × c
    blocks for pivots of shape (L, c, c). One grouping factor's intercepts give the
    diagonal, its correlated intercepts and slopes the blocks; building the blocks
    alone spares forming (and scaling) a dense q × q matrix at every Newton step.
    """

    pivots: np.ndarray
    coupling: np.ndarray
    rest: np.ndarray


class Factor:
    """Solve with, and take the log-determinant of, a symmetric positive-definite matrix.

    *blocks* is eliminated by its diagonal block's Schur complement (one grouping
    factor's intercepts first), so a thousand participants' intercepts cost a division
    instead of a share of a q³ Cholesky factorisation; :meth:`of` wraps a factor made
    elsewhere (analysis.mixed.cholesky's sparse LDLᵀ).
    """

    def __init__(self, blocks: Blocks):
        self._eliminate(blocks.pivots, blocks.coupling, blocks.rest)

    @classmethod
    def of(cls, logdet: float, solve) -> "Factor":
        """Return a factor already computed elsewhere: its log det and its solver."""
        factor = cls.__new__(cls)
        factor.logdet, factor.solve = logdet, solve
        return factor

    def _eliminate(self, pivots: np.ndarray, coupling: np.ndarray, rest: np.ndarray) -> None:
        """Factor [[diag(pivots), coupling], [couplingᵀ, rest]] by its Schur complement."""
        if pivots.ndim == 3:
            self._eliminate_blocks(pivots, coupling, rest)
            return
        k = len(pivots)
        if rest.size == 0:
            self.logdet = float(np.log(pivots).sum())
            self.solve = lambda rhs: rhs / (pivots if np.ndim(rhs) == 1 else pivots[:, None])
            return
        schur = rest - coupling.T @ (coupling / pivots[:, None])
        factor = linalg.cho_factor(schur, lower=True, check_finite=False)
        self.logdet = float(np.log(pivots).sum() + 2 * np.log(np.diag(factor[0])).sum())

        def solve(rhs: np.ndarray) -> np.ndarray:
            rhs = np.asarray(rhs, dtype=float)
            divisor = pivots if rhs.ndim == 1 else pivots[:, None]
            head = rhs[:k] / divisor
            tail = linalg.cho_solve(factor, rhs[k:] - coupling.T @ head, check_finite=False)
            return np.concatenate([head - coupling @ tail / divisor, tail])

        self.solve = solve

    def _eliminate_blocks(self, pivots: np.ndarray, coupling: np.ndarray, rest: np.ndarray):
        """Factor [[P, coupling], [couplingᵀ, rest]] with P block diagonal (L, c, c)."""
        levels, c, _ = pivots.shape
        k = levels * c
        cholesky = np.linalg.cholesky(pivots)
        logdet = float(2 * np.log(np.diagonal(cholesky, axis1=1, axis2=2)).sum())

        def head_solve(rhs: np.ndarray) -> np.ndarray:
            shaped = rhs.reshape(levels, c, -1)
            return np.linalg.solve(pivots, shaped).reshape(rhs.shape)

        if rest.size == 0:
            self.logdet, self.solve = logdet, head_solve
            return
        solved_coupling = head_solve(coupling)
        factor = linalg.cho_factor(rest - coupling.T @ solved_coupling, lower=True)
        self.logdet = logdet + float(2 * np.log(np.diag(factor[0])).sum())

        def solve(rhs: np.ndarray) -> np.ndarray:
            rhs = np.asarray(rhs, dtype=float)
            head = head_solve(rhs[:k])
            tail = linalg.cho_solve(factor, rhs[k:] - coupling.T @ head, check_finite=False)
            return np.concatenate([head - solved_coupling @ tail, tail])

        self.solve = solve
