"""Frozen results of the mixed-effects models; reports render them, never recompute.

Each model result has ``statistic``/``df``/``pvalue`` (the Wald χ² test that all
conditions are alike), ``nobs``, ``summary()`` (a plain-text table), ``to_dict()`` and
``apa()``.
"""

import dataclasses

from analysis.results import Result, format_p


def _two(value: float) -> str:
    return f"{value:.2f}".replace("-0.00", "0.00")


@dataclasses.dataclass(frozen=True)
class Coefficient(Result):
    """One fixed effect with its Wald z test and 95 % CI (scale of the linear predictor)."""

    name: str
    estimate: float
    se: float
    statistic: float
    pvalue: float
    ci: tuple[float, float]


@dataclasses.dataclass(frozen=True)
class VarianceComponent(Result):
    """One random effect's standard deviation, over ``levels`` levels of ``group``."""

    name: str
    group: str
    sd: float
    variance: float
    levels: int


@dataclasses.dataclass(frozen=True)
class Contrast(Result):
    """The difference a − b of two conditions' effects, Wald z test, corrected p, 95 % CI."""

    a: str
    b: str
    estimate: float
    se: float
    statistic: float
    pvalue: float
    pvalue_adjusted: float
    ci: tuple[float, float]

    def apa(self) -> str:
        return (
            f"{self.a} − {self.b} = {_two(self.estimate)} "
            f"[{_two(self.ci[0])}, {_two(self.ci[1])}], z = {_two(self.statistic)}, "
            f"{format_p(self.pvalue)} "
            f"({format_p(self.pvalue_adjusted).replace('p', 'p_adj', 1)})"
        )


@dataclasses.dataclass(frozen=True)
class ProportionalOddsTest(Result):
    """Likelihood-ratio test of proportional odds against condition effects per threshold.

    The check of R's ``ordinal::nominal_test``, on the model without random effects.
    """

    statistic: float
    df: int
    pvalue: float
    holds: bool

    def apa(self) -> str:
        verdict = "holds" if self.holds else "is doubtful"
        return (
            f"proportional odds {verdict}: LR χ²({self.df}) = {self.statistic:.2f}, "
            f"{format_p(self.pvalue)}"
        )


@dataclasses.dataclass(frozen=True)
class _ModelResult(Result):
    """What every mixed model reports (the common fields come first)."""

    model: str
    estimator: str
    formula: str
    conditions: tuple[str, ...]
    reference: str
    effects: tuple[Coefficient, ...]
    contrasts: tuple[Contrast, ...]
    random: tuple[VarianceComponent, ...]
    statistic: float
    df: int
    pvalue: float
    nobs: int
    participants: int
    items: int
    loglik: float
    aic: float
    converged: bool
    correction: str
    notes: tuple[str, ...]

    def apa(self) -> str:
        return f"Wald χ²({self.df}) = {self.statistic:.2f}, {format_p(self.pvalue)}"

    def _lines(self) -> list[str]:
        lines = [
            f"{self.model}: {self.formula}",
            f"{self.estimator}; {self.nobs} observations, {self.participants} participants, "
            f"{self.items} items; log-likelihood {self.loglik:.2f}, AIC {self.aic:.1f}"
            + ("" if self.converged else " — NOT CONVERGED"),
            "",
            f"{'effect':<28}{'estimate':>10}{'SE':>8}{'z':>8}{'p':>10}   95 % CI",
        ]
        for c in self._rows():
            lines.append(
                f"{c.name:<28}{c.estimate:>10.3f}{c.se:>8.3f}{c.statistic:>8.2f}"
                f"{format_p(c.pvalue).removeprefix('p = ').removeprefix('p '):>10}   "
                f"[{c.ci[0]:.3f}, {c.ci[1]:.3f}]"
            )
        lines += ["", f"{'random effect':<36}{'SD':>8}{'levels':>8}"]
        for r in self.random:
            lines.append(f"{r.name:<36}{r.sd:>8.3f}{r.levels:>8}")
        lines += ["", f"conditions alike: {self.apa()}"]
        lines += [f"contrast {c.apa()}" for c in self.contrasts]
        lines += [f"note: {note}" for note in self.notes]
        return lines

    def _rows(self) -> tuple[Coefficient, ...]:
        return self.effects

    def summary(self) -> str:
        return "\n".join(self._lines())


@dataclasses.dataclass(frozen=True)
class MixedBradleyTerryResult(_ModelResult):
    """Mixed-effects Bradley–Terry model of paired choices (logistic, or Davidson with ties).

    ``effects`` holds each condition's log-worth relative to ``reference`` (0) and,
    named "position (clip 1)", the log-odds of choosing the first clip between equals.
    """

    position: Coefficient | None = None
    tie_handling: str = "exclude"
    tie_parameter: float | None = None

    def _rows(self) -> tuple[Coefficient, ...]:
        return ((self.position,) if self.position else ()) + self.effects


@dataclasses.dataclass(frozen=True)
class CumulativeLinkMixedResult(_ModelResult):
    """Cumulative-logit mixed model of ratings: effects are log odds ratios of rating higher."""

    question: str = ""
    thresholds: tuple[Coefficient, ...] = ()
    proportional_odds: ProportionalOddsTest | None = None

    def _rows(self) -> tuple[Coefficient, ...]:
        return self.effects + self.thresholds

    def _lines(self) -> list[str]:
        lines = super()._lines()
        if self.proportional_odds is not None:
            lines.append(self.proportional_odds.apa())
        return lines


@dataclasses.dataclass(frozen=True)
class LinearMixedResult(_ModelResult):
    """Linear mixed model of ratings as numbers (REML): effects are differences of means."""

    question: str = ""
    residual_sd: float = float("nan")


@dataclasses.dataclass(frozen=True)
class MixedModels(Result):
    """The report's "Mixed models" section: one pairwise model and the rating models."""

    pairwise: MixedBradleyTerryResult | None
    ordinal: tuple[CumulativeLinkMixedResult, ...]
    linear: tuple[LinearMixedResult, ...]
    skipped: tuple[str, ...] = ()
