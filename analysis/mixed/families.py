"""Conditional log-likelihoods of one observation given its linear predictor η.

Each family returns, per observation, the log-likelihood, its first derivative in η
and the negative second derivative in η (the weight of a Newton step). All the
families are log-concave in η, so the weights are positive and the conditional mode of
the random effects is unique.
"""

import dataclasses
from typing import Protocol

import numpy as np
from scipy.special import expit, gammaln, log_expit


@dataclasses.dataclass(frozen=True)
class Derivatives:
    """Per-observation log-likelihood ``loglik``, ``gradient`` dℓ/dη and ``weight`` −d²ℓ/dη²."""

    loglik: np.ndarray
    gradient: np.ndarray
    weight: np.ndarray


class Family(Protocol):
    """What the fits ask of a family: its name, derivatives in η, its parameters beyond
    η (names, start, natural and free scales) and draws for simulation."""

    @property
    def name(self) -> str: ...

    def derivatives(self, eta: np.ndarray, y: np.ndarray, extra: np.ndarray) -> Derivatives: ...

    def extra_names(self, y: np.ndarray) -> tuple[str, ...]: ...

    def extra_start(self, y: np.ndarray) -> np.ndarray: ...

    def extra_natural(self, free: np.ndarray) -> np.ndarray: ...

    def extra_free(self, natural: np.ndarray) -> np.ndarray: ...

    def simulate(
        self, eta: np.ndarray, extra: np.ndarray, rng: np.random.Generator
    ) -> np.ndarray: ...


class NoExtraParameters:
    """What a family without parameters beyond η answers about them (the logistic ones)."""

    def extra_names(self, y: np.ndarray) -> tuple[str, ...]:
        return ()

    def extra_start(self, y: np.ndarray) -> np.ndarray:
        return np.zeros(0)

    def extra_natural(self, free: np.ndarray) -> np.ndarray:
        return free

    def extra_free(self, natural: np.ndarray) -> np.ndarray:
        return natural


@dataclasses.dataclass(frozen=True)
class Bernoulli(NoExtraParameters):
    """Logistic regression: P(y = 1) = logit⁻¹(η); y is 0 or 1."""

    name: str = "binomial (logit link)"

    def derivatives(self, eta: np.ndarray, y: np.ndarray, extra: np.ndarray) -> Derivatives:
        p = expit(eta)
        loglik = y * log_expit(eta) + (1 - y) * log_expit(-eta)
        return Derivatives(loglik, y - p, p * (1 - p))

    def simulate(self, eta: np.ndarray, extra: np.ndarray, rng: np.random.Generator):
        return (rng.random(eta.shape) < expit(eta)).astype(float)


@dataclasses.dataclass(frozen=True, eq=False)
class Binomial(NoExtraParameters):
    """Logistic regression on counts: y successes of *trials* (one count per observation),
    P(success) = logit⁻¹(η); as R's ``glmer(cbind(y, trials − y) ~ …, binomial)``, the
    log-likelihood includes log C(trials, y)."""

    trials: np.ndarray
    name: str = "binomial with trials (logit link)"

    def __post_init__(self) -> None:
        trials = np.asarray(self.trials, dtype=float)
        if trials.ndim != 1 or np.any(trials < 1) or np.any(trials != np.round(trials)):
            raise ValueError("Binomial trials must be whole numbers of at least 1.")
        object.__setattr__(self, "trials", trials)

    def extra_start(self, y: np.ndarray) -> np.ndarray:
        if np.any(y < 0) or np.any(y > self.trials) or np.any(y != np.round(y)):
            raise ValueError("Binomial successes must be whole numbers from 0 to the trials.")
        return np.zeros(0)

    def derivatives(self, eta: np.ndarray, y: np.ndarray, extra: np.ndarray) -> Derivatives:
        n, p = self.trials, expit(eta)
        choose = gammaln(n + 1) - gammaln(y + 1) - gammaln(n - y + 1)
        loglik = y * log_expit(eta) + (n - y) * log_expit(-eta) + choose
        return Derivatives(loglik, y - n * p, n * p * (1 - p))

    def simulate(self, eta: np.ndarray, extra: np.ndarray, rng: np.random.Generator):
        return rng.binomial(self.trials.astype(int), expit(eta)).astype(float)


# Davidson outcome codes: the first-named option won, the second won, or a tie.
FIRST, SECOND, TIE = 1.0, 0.0, 0.5


@dataclasses.dataclass(frozen=True)
class Davidson:
    """Paired comparison with ties (Davidson 1970) in log-worth difference η.

    P(first) = e^{η/2} / D, P(second) = e^{−η/2} / D, P(tie) = ν / D with
    D = e^{η/2} + e^{−η/2} + ν; the one extra parameter is log ν. With ν → 0 it is the
    Bradley–Terry logistic model. y is 1 (first), 0 (second) or 0.5 (tie).
    """

    name: str = "Davidson (paired comparison with ties)"

    def extra_names(self, y: np.ndarray) -> tuple[str, ...]:
        return ("log_nu",)

    def extra_start(self, y: np.ndarray) -> np.ndarray:
        ties = max(float(np.mean(y == TIE)), 1e-3)
        # At η = 0 a tie has probability ν / (2 + ν).
        return np.array([np.log(2 * ties / (1 - ties))])

    def extra_natural(self, free: np.ndarray) -> np.ndarray:
        return free

    def extra_free(self, natural: np.ndarray) -> np.ndarray:
        return natural

    def derivatives(self, eta: np.ndarray, y: np.ndarray, extra: np.ndarray) -> Derivatives:
        log_nu = float(extra[0])
        terms = np.stack([eta / 2, -eta / 2, np.full_like(eta, log_nu)])
        top = terms.max(axis=0)
        scaled = np.exp(terms - top)
        total = scaled.sum(axis=0)
        log_d = top + np.log(total)
        a, b, _ = scaled / total
        # dlogD/dη = (a − b)/2 and d²logD/dη² = (a + b)/4 − ((a − b)/2)², a, b shares of D.
        mean = (a - b) / 2
        weight = (a + b) / 4 - mean**2
        own = np.select([y == FIRST, y == SECOND], [eta / 2, -eta / 2], default=log_nu)
        slope = np.select([y == FIRST, y == SECOND], [0.5, -0.5], default=0.0)
        return Derivatives(own - log_d, slope - mean, weight)

    def simulate(self, eta: np.ndarray, extra: np.ndarray, rng: np.random.Generator):
        nu = float(np.exp(extra[0]))
        first, second = np.exp(eta / 2), np.exp(-eta / 2)
        total = first + second + nu
        draw = rng.random(eta.shape) * total
        return np.where(draw < first, FIRST, np.where(draw < first + second, SECOND, TIE))


@dataclasses.dataclass(frozen=True)
class CumulativeLogit:
    """Proportional-odds model: P(Y ≤ k) = logit⁻¹(θ_k − η), k = 0 … K − 2.

    The parametrisation of R's ``ordinal::clmm``; y holds category indices 0 … K − 1.
    The extra parameters are the K − 1 increasing thresholds θ, optimised as θ₀ and
    the logs of the gaps so that they stay ordered.
    """

    categories: int
    name: str = "cumulative logit (proportional odds)"

    def extra_names(self, y: np.ndarray) -> tuple[str, ...]:
        return tuple(f"threshold {k + 1}|{k + 2}" for k in range(self.categories - 1))

    def extra_start(self, y: np.ndarray) -> np.ndarray:
        counts = np.bincount(y.astype(int), minlength=self.categories) + 0.5
        cumulative = np.cumsum(counts)[:-1] / counts.sum()
        return self.extra_free(np.log(cumulative / (1 - cumulative)))

    def extra_natural(self, free: np.ndarray) -> np.ndarray:
        return np.cumsum(np.concatenate([free[:1], np.exp(free[1:])]))

    def extra_free(self, natural: np.ndarray) -> np.ndarray:
        return np.concatenate([natural[:1], np.log(np.maximum(np.diff(natural), 1e-12))])

    def derivatives(self, eta: np.ndarray, y: np.ndarray, extra: np.ndarray) -> Derivatives:
        bounds = np.concatenate([[-np.inf], extra, [np.inf]])
        k = y.astype(int)
        upper, lower = bounds[k + 1] - eta, bounds[k] - eta
        f_up, f_low = expit(upper), expit(lower)
        # P = F(upper) − F(lower) loses all digits in a tail; the same difference from
        # the other side, 1 − F, keeps them there.
        prob = np.where(upper + lower > 0, expit(-lower) - expit(-upper), f_up - f_low)
        prob = np.maximum(prob, 1e-300)
        dens_up, dens_low = f_up * (1 - f_up), f_low * (1 - f_low)
        slope_up, slope_low = dens_up * (1 - 2 * f_up), dens_low * (1 - 2 * f_low)
        gradient = -(dens_up - dens_low) / prob
        second = (slope_up - slope_low) / prob - gradient**2
        return Derivatives(np.log(prob), gradient, -second)

    def simulate(self, eta: np.ndarray, extra: np.ndarray, rng: np.random.Generator):
        cumulative = expit(extra[None, :] - eta[:, None])
        draw = rng.random(eta.shape)
        return (draw[:, None] > cumulative).sum(axis=1).astype(float)
