"""Check a mixed model's optimum as lme4's ``checkConv`` does, and name a singular fit.

At the optimum of the deviance −2ℓ over the parameters not on a bound: the gradient
scaled by the Hessian's Cholesky factor, min(|R⁻ᵀg|, |g|), must be below 0.002 in every
component, and the Hessian must be positive definite (lme4 1.1-31, ``checkConv`` with
``check.conv.grad = .makeCC("warning", tol = 2e-3)`` and ``check.conv.hess``). A fit is
singular when a variance parameter sits on its bound of zero (``isSingular``, tolerance
1e-4): the data cannot tell that random effect from none, and the model should be
simplified.
"""

import dataclasses

import numpy as np
from statsmodels.tools.numdiff import approx_fprime, approx_hess3

GRADIENT_TOL = 2e-3
# Eigenvalues of the Hessian below −this are negative (lme4's check.conv.hess tol 1e-6).
EIGEN_TOL = 1e-6

SINGULAR_NOTE = (
    "Singular (boundary) fit: the {names} SD{s} {are} estimated at zero, so the data "
    "cannot tell {them} from no random effect; simplify the random effects (drop {them}) "
    "or read the fixed effects with care."
)


@dataclasses.dataclass(frozen=True)
class Convergence:
    """What the checks found: the largest scaled gradient, the Hessian, and the words."""

    max_gradient: float
    hessian_positive_definite: bool
    messages: tuple[str, ...]

    @property
    def ok(self) -> bool:
        return not self.messages


def check(deviance, x: np.ndarray, free: np.ndarray, hessian: np.ndarray | None = None):
    """Check the optimum *x* of *deviance* over the parameters marked *free* (boolean mask).

    *hessian* of the deviance over the free parameters may be passed when already known.
    """
    x = np.asarray(x, float)
    index = np.flatnonzero(free)
    if index.size == 0:
        return Convergence(0.0, True, ())

    def restricted(values):
        full = x.copy()
        full[index] = values
        return deviance(full)

    gradient = approx_fprime(x[index], restricted, centered=True)
    if hessian is None:
        hessian = approx_hess3(x[index], restricted)
    messages = []
    eigenvalues = np.linalg.eigvalsh((hessian + hessian.T) / 2)
    positive = bool(np.all(eigenvalues > EIGEN_TOL))
    if not positive:
        negative = int(np.sum(eigenvalues < -EIGEN_TOL))
        messages.append(
            f"degenerate Hessian with {negative} negative eigenvalue"
            + ("s" if negative != 1 else "")
            if negative
            else "the Hessian is numerically singular: a parameter is not identified"
        )
        largest = float(np.max(np.abs(gradient)))
    else:
        scaled = np.linalg.solve(np.linalg.cholesky(hessian).T, gradient)
        largest = float(np.max(np.minimum(np.abs(scaled), np.abs(gradient))))
    if largest > GRADIENT_TOL:
        messages.append(
            f"failed to converge with max|grad| = {largest:.3g} (tol = {GRADIENT_TOL:g})"
        )
    return Convergence(largest, positive, tuple(messages))


def singular_note(names) -> str:
    """Return the note for components estimated at zero (names in their order)."""
    names = list(names)
    many = len(names) > 1
    return SINGULAR_NOTE.format(
        names=" and ".join(names),
        s="s" if many else "",
        are="are" if many else "is",
        them="them" if many else "it",
    )
