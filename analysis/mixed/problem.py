"""The parts of a mixed model: variance components, the problem, the fitted result."""

import dataclasses

import numpy as np

from analysis.mixed.families import Bernoulli, Family

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
    The columns share one SD unless ``correlated``: then they have an unstructured
    covariance, lme4's ``(1 + x | group)`` (linear mixed models only).
    """

    name: str
    group: str
    levels: tuple[str, ...]
    columns: tuple[str, ...]
    codes: np.ndarray
    values: np.ndarray
    correlated: bool = False

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
        *,
        correlated: bool = False,
    ) -> "Component":
        """Build the component for level codes (n_obs,) and per-level values (n_obs, c)."""
        codes = np.asarray(codes, dtype=np.int64)
        values = np.ones((len(codes), 1)) if values is None else np.asarray(values, float)
        return cls(
            name,
            group,
            tuple(levels),
            tuple(columns),
            codes,
            values.reshape(len(codes), -1),
            correlated,
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
    family: Family = dataclasses.field(default_factory=Bernoulli)


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
    # A variance component on its bound of zero (lme4's isSingular), and what the
    # convergence checks found wrong (analysis.mixed.convergence), if anything.
    singular: bool = False
    checks: tuple[str, ...] = ()
    # Fixed-effect columns dropped because they repeat others (analysis.mixed.degenerate).
    dropped: tuple[str, ...] = ()
