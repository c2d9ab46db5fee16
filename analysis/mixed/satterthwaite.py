"""Satterthwaite degrees of freedom for a linear mixed model's fixed effects (lmerTest's).

For a contrast l, var(lβ̂) = l C(φ) lᵀ with C(φ) = σ² R⁻¹ as a function of the variance
parameters φ = (θ, σ); with g = ∂(l C lᵀ)/∂φ and A = 2 H⁻¹, H the Hessian of the
deviance in φ at the optimum,

    ν = 2 (l C lᵀ)² / (gᵀ A g)

(Kuznetsova, Brockhoff & Christensen 2017, J. Stat. Softw. 82(13) §3.3, eq. 3). For a
q-row L the F statistic is β̂ᵀLᵀ(LCLᵀ)⁻¹Lβ̂ / q, and its denominator df combines the
eigen-contrasts' ν_m as E = Σ ν_m/(ν_m − 2), ν = 2E/(E − q) (ibid. eq. 5; 2 where any
ν_m ≤ 2; their mean where they are all equal). Derivatives are numerical, as
lmerTest's (numDeriv).
"""

import dataclasses

import numpy as np
from scipy import stats
from statsmodels.tools.numdiff import approx_fprime, approx_hess3

from analysis.mixed.lmm import LinearFit


@dataclasses.dataclass(frozen=True, eq=False)
class Satterthwaite:
    """What every contrast's df needs: cov(β̂), its derivatives J and A = 2 H⁻¹."""

    cov: np.ndarray
    jacobian: np.ndarray
    a: np.ndarray

    @classmethod
    def of(cls, fit: LinearFit) -> "Satterthwaite":
        """Differentiate *fit*'s deviance and cov(β̂) at its optimum."""
        varpar = np.concatenate([fit.theta, [fit.sigma]])
        criterion = fit.criterion
        hessian = approx_hess3(varpar, criterion.deviance)
        a = 2 * np.linalg.pinv(hessian)
        p = len(fit.beta)
        jacobian = approx_fprime(
            varpar, lambda v: criterion.covbeta(v).ravel(), centered=True
        ).reshape(p, p, len(varpar))
        return cls(cov=fit.cov, jacobian=jacobian, a=a)

    def df(self, contrast: np.ndarray) -> float:
        """Return ν for one contrast vector l."""
        contrast = np.asarray(contrast, float)
        variance = contrast @ self.cov @ contrast
        gradient = np.einsum("i,ijk,j->k", contrast, self.jacobian, contrast)
        spread = gradient @ self.a @ gradient
        return float(2 * variance**2 / spread) if spread > 0 else float("inf")

    def f_test(self, rows: np.ndarray, beta: np.ndarray) -> tuple[float, int, float, float]:
        """Return (F, q, ν, p) for Lβ = 0 (lmerTest's ``contestMD``)."""
        rows = np.atleast_2d(np.asarray(rows, float))
        q = rows.shape[0]
        values, vectors = np.linalg.eigh(rows @ self.cov @ rows.T)
        eigen_rows = vectors.T @ rows
        f = float(np.sum((eigen_rows @ beta) ** 2 / values) / q)
        nus = np.array([self.df(row) for row in eigen_rows])
        if q == 1:
            nu = float(nus[0])
        elif np.all(np.abs(np.diff(nus)) < 1e-8):
            nu = float(nus.mean())
        elif np.any(nus <= 2):
            nu = 2.0
        else:
            e = float(np.sum(nus / (nus - 2)))
            nu = 2 * e / (e - q)
        return f, q, nu, float(stats.f.sf(f, q, nu))
