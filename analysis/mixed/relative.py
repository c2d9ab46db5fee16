"""Form ΛᵀZᵀZΛ + I, ΛᵀZᵀX and ΛᵀZᵀy at any θ without passing over the observations.

Λ is block diagonal, one relative factor T_k per level of component k (lme4's Λ_θ; Bates
et al. 2015, J. Stat. Softw. 67(1) §2.2), and ZΛ's row i holds, in component k's
columns of its level, z_ik T_k. So an entry of ΛᵀZᵀZΛ is Σ_ab T[a, f] T[b, s] G_ab,
where G_ab sums z_a z_b over the observations that meet in that entry. The G are
formed once per problem in ZᵀZ's sparse pattern (analysis.mixed.cholesky); each θ then
costs a small product per stored entry, whatever the number of observations: the
correlated slopes of 1,000 participants × 48 ratings take 48,000 rows out of every
evaluation.
"""

import numpy as np

from analysis.mixed.modes import ConditionalModes


def _row_spans(state: ConditionalModes) -> list[tuple[int, int, int]]:
    """Return, per column of Z's row-wise layout, its component and that component's
    first position and width in the layout."""
    spans, at = [], 0
    for k in state.order:
        width = len(state.problem.components[k].columns)
        spans += [(k, at, width)] * width
        at += width
    return spans


class RelativeCross:
    """ΛᵀZᵀZΛ + I in the state's sparse pattern, and Λᵀ times Zᵀ's products, for any Λ."""

    def __init__(self, state: ConditionalModes):
        self.state = state
        spans = _row_spans(state)
        n = state.n
        slots = state.pair_slots.reshape(n, -1)
        self.terms = []
        for t, (f, s) in enumerate(zip(*state.pair_columns, strict=True)):
            kf, f0, cf = spans[f]
            ks, s0, cs = spans[s]
            unique, inverse = np.unique(slots[:, t], return_inverse=True)
            products = state.vals[:, f0 : f0 + cf, None] * state.vals[:, None, s0 : s0 + cs]
            sums = np.column_stack(
                [
                    np.bincount(inverse, column, minlength=len(unique))
                    for column in products.reshape(n, -1).T
                ]
            )
            self.terms.append((unique, sums, kf, f - f0, ks, s - s0))
        self.slots = np.concatenate([term[0] for term in self.terms])
        components = state.problem.components
        self.columns = [
            state.position[state.offsets[k] : state.offsets[k + 1]].reshape(
                len(components[k].levels), len(components[k].columns)
            )
            for k in range(len(components))
        ]

    def identity_plus(self, factors: list[np.ndarray]) -> np.ndarray:
        """Return I + ΛᵀZᵀZΛ's values in the pattern's slots for the factors T_k."""
        chunks = [
            sums @ np.outer(factors[kf][:, jf], factors[ks][:, js]).ravel()
            for _, sums, kf, jf, ks, js in self.terms
        ]
        pattern = self.state.pattern
        values = np.bincount(self.slots, np.concatenate(chunks), minlength=len(pattern.keys))
        values[pattern.diagonal] += 1.0
        return values

    def transposed_times(self, factors: list[np.ndarray], matrix: np.ndarray) -> np.ndarray:
        """Return Λᵀ matrix for *matrix* in Z's columns (q,) or (q, m)."""
        out = np.empty_like(matrix)
        for columns, factor in zip(self.columns, factors, strict=True):
            block = matrix[columns]  # (levels, c) or (levels, c, m)
            out[columns] = np.einsum("ab,la...->lb...", factor, block)
        return out
