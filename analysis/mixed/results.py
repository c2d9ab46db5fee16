"""Frozen results of the mixed-effects models; reports render them, never recompute.

Each model result has ``statistic``/``df``/``pvalue`` (the Wald χ² test that all
conditions are alike), ``nobs``, ``summary()`` (a plain-text table), ``to_dict()`` and
``apa()``.
"""

import dataclasses
from collections.abc import Sequence
from typing import Any, Self

import pandas as pd

from analysis.results import Result, format_p


def _two(value: float) -> str:
    return f"{value:.2f}".replace("-0.00", "0.00")


@dataclasses.dataclass(frozen=True)
class Coefficient(Result):
    """One fixed effect with its test and 95 % CI (scale of the linear predictor).

    A Wald z test, or with ``df`` (Satterthwaite's, linear models) a t test.
    """

    name: str
    estimate: float
    se: float
    statistic: float
    pvalue: float
    ci: tuple[float, float]
    df: float | None = None


@dataclasses.dataclass(frozen=True)
class VarianceComponent(Result):
    """One random effect's standard deviation, over ``levels`` levels of ``group``.

    ``column`` is what varies by level (the intercept, or a condition's effect), and
    ``ci`` the profile-likelihood 95 % CI of the SD where it was computed.
    """

    name: str
    group: str
    sd: float
    variance: float
    levels: int
    column: str = "(Intercept)"
    ci: tuple[float, float] | None = None


@dataclasses.dataclass(frozen=True)
class Correlation(Result):
    """The correlation of two random effects of one grouping factor (lme4's ``(x | g)``)."""

    group: str
    a: str
    b: str
    r: float


@dataclasses.dataclass(frozen=True)
class LikelihoodRatioTest(Result):
    """A likelihood-ratio test of nested models fitted by ML (R's ``anova(m0, m1)``)."""

    reduced: str
    full: str
    statistic: float
    df: int
    pvalue: float
    loglik_reduced: float
    loglik_full: float

    def apa(self) -> str:
        return f"LR χ²({self.df}) = {self.statistic:.2f}, {format_p(self.pvalue)}"


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
    df: float | None = None

    def apa(self) -> str:
        test = "z" if self.df is None else f"t({self.df:.1f})"
        return (
            f"{self.a} − {self.b} = {_two(self.estimate)} "
            f"[{_two(self.ci[0])}, {_two(self.ci[1])}], {test} = {_two(self.statistic)}, "
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
    # A variance component on its bound of zero (lme4's isSingular): named in summary()
    # and apa() as well as in the notes.
    singular: bool = False

    @classmethod
    def from_fit(
        cls,
        fit: Any,
        data: pd.DataFrame,
        order: Sequence[str],
        *,
        test: tuple[float, int, float],
        notes: Sequence[str],
        n_params: int | None = None,
        **fields: Any,
    ) -> Self:
        """Build the result of *fit* to *data*: the fields every mixed model fills alike.

        *fit* is a linear or a Laplace fit (``nobs``, ``loglik``, ``converged``,
        ``singular``); *test* is the conditions-alike test's (statistic, df, p);
        *n_params* counts the estimated parameters for the AIC (−2 log L + 2k): a
        Laplace fit's fixed effects, extra parameters and SDs unless given.
        """
        statistic, df, pvalue = test
        if n_params is None:
            n_params = len(fit.params) + len(fit.sd)
        return cls(
            conditions=tuple(order),
            reference=order[0],
            statistic=statistic,
            df=df,
            pvalue=pvalue,
            nobs=fit.nobs,
            participants=int(data["participant"].nunique()),
            items=int(data["item"].nunique()),
            loglik=fit.loglik,
            aic=-2 * fit.loglik + 2 * n_params,
            converged=fit.converged,
            singular=fit.singular,
            notes=tuple(notes),
            **fields,
        )

    def apa(self) -> str:
        if not self.converged:
            # A fit that stopped short of its optimum has no covariance to test with.
            return "not tested: the fit did not converge (no Wald test on its covariance)"
        return self._test() + (
            " (singular fit: a random-effect SD estimated at zero)" if self.singular else ""
        )

    def _test(self) -> str:
        """Return the test that the conditions are alike, APA style."""
        return f"Wald χ²({self.df}) = {self.statistic:.2f}, {format_p(self.pvalue)}"

    def _lines(self) -> list[str]:
        lines = [
            f"{self.model}: {self.formula}",
            f"{self.estimator}; {self.nobs} observations, {self.participants} participants, "
            f"{self.items} items; log-likelihood {self.loglik:.2f}, AIC {self.aic:.1f}"
            + ("" if self.converged else " — NOT CONVERGED")
            + (" — SINGULAR (boundary) FIT" if self.singular else ""),
            "",
        ]
        rows = self._rows()
        with_df = any(c.df is not None for c in rows)
        lines.append(
            f"{'effect':<28}{'estimate':>10}{'SE':>8}"
            + (f"{'df':>8}{'t':>8}" if with_df else f"{'z':>8}")
            + f"{'p':>10}   95 % CI"
        )
        for c in rows:
            df = "" if not with_df else f"{c.df:>8.1f}" if c.df is not None else " " * 8
            lines.append(
                f"{c.name:<28}{c.estimate:>10.3f}{c.se:>8.3f}{df}{c.statistic:>8.2f}"
                f"{format_p(c.pvalue).removeprefix('p = ').removeprefix('p '):>10}   "
                f"[{c.ci[0]:.3f}, {c.ci[1]:.3f}]"
            )
        lines += ["", f"{'random effect':<36}{'SD':>8}{'levels':>8}   95 % CI (profile)"]
        for r in self.random:
            label = r.name if r.column == "(Intercept)" else f"{r.name}: {r.column}"
            ci = "" if r.ci is None else f"   [{r.ci[0]:.3f}, {r.ci[1]:.3f}]"
            lines.append(f"{label:<36}{r.sd:>8.3f}{r.levels:>8}{ci}")
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
    """Linear mixed model of ratings as numbers (REML or ML): effects are differences of means.

    ``statistic``/``df``/``pvalue`` are the F test that the conditions are alike, with
    Satterthwaite's denominator df ``den_df`` (lmerTest's ``anova``); effects and
    contrasts carry t tests with their own df. ``likelihood_ratio`` tests the same
    hypothesis by ML refits, as R's ``anova(m0, m1)``.
    """

    question: str = ""
    residual_sd: float = float("nan")
    residual_sd_ci: tuple[float, float] | None = None
    reml: bool = True
    den_df: float = float("nan")
    likelihood_ratio: LikelihoodRatioTest | None = None
    correlations: tuple[Correlation, ...] = ()

    def _test(self) -> str:
        return f"F({self.df}, {self.den_df:.1f}) = {self.statistic:.2f}, {format_p(self.pvalue)}"

    def _lines(self) -> list[str]:
        lines = super()._lines()
        lines += [
            f"random-effect correlation {c.group} {c.a}–{c.b}: r = {c.r:.2f}"
            for c in self.correlations
        ]
        if self.likelihood_ratio is not None:
            lines.append(f"conditions alike (ML refits): {self.likelihood_ratio.apa()}")
        return lines


@dataclasses.dataclass(frozen=True)
class MixedModels(Result):
    """The report's "Mixed models" section: one pairwise model and the rating models."""

    pairwise: MixedBradleyTerryResult | None
    ordinal: tuple[CumulativeLinkMixedResult, ...]
    linear: tuple[LinearMixedResult, ...]
    skipped: tuple[str, ...] = ()
