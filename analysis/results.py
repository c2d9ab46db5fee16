"""Frozen result objects returned by every analysis; reports render them, never recompute.

Each has ``to_dict()`` (JSON-ready) and, where a test is involved, ``apa()`` giving the
APA-style sentence fragment a paper uses.
"""

import dataclasses
import math
from decimal import ROUND_HALF_UP, Decimal
from typing import Any


def plain(value: Any) -> Any:
    """Convert numpy scalars, tuples and NaN to JSON-ready Python values."""
    if isinstance(value, dict):
        return {key: plain(item) for key, item in value.items()}
    if isinstance(value, list | tuple):
        return [plain(item) for item in value]
    if hasattr(value, "item") and not isinstance(value, str):
        value = value.item()
    if isinstance(value, float) and not math.isfinite(value):
        return None
    return value


class Result:
    """Mixin giving dataclass results a JSON-ready ``to_dict``."""

    def to_dict(self) -> dict[str, Any]:
        return plain(dataclasses.asdict(self))  # type: ignore[call-overload]  # a dataclass


def rendered(value: Any) -> Any:
    """Render results in their own vocabulary, JSON-ready: each one's fields (nested results
    rendered alike), with its APA sentence and, for a model, its plain-text summary."""
    if isinstance(value, Result) and dataclasses.is_dataclass(value):
        data = {f.name: rendered(getattr(value, f.name)) for f in dataclasses.fields(value)}
        for name in ("apa", "summary"):
            if callable(getattr(value, name, None)):
                data[name] = getattr(value, name)()
        return plain(data)
    if isinstance(value, list | tuple):
        return [rendered(item) for item in value]
    return plain(value)


def format_p(pvalue: float) -> str:
    """Format a p-value the APA way: "p = .043", "p < .001" (no leading zero)."""
    if pvalue is None or not math.isfinite(pvalue):
        return "p = n/a"
    if pvalue < 0.001:
        return "p < .001"
    return "p = " + f"{pvalue:.3f}".lstrip("0")


def round_half_up(value: float, digits: int = 2) -> float:
    """Round like published tables do (15.625 → 15.63), not to even like round()."""
    quantum = Decimal(1).scaleb(-digits)
    return float(Decimal(repr(value)).quantize(quantum, rounding=ROUND_HALF_UP))


def _two(value: float) -> str:
    return f"{value:.2f}".replace("-0.00", "0.00")


def proportion_text(value: float) -> str:
    """Return a quantity that cannot exceed 1 (η², a share) to two places, without the
    leading zero, as APA writes it."""
    return _two(value).lstrip("0")


def few_named(ids, limit: int = 5) -> str:
    """Return the first *limit* of *ids* comma-separated, "…" when there are more."""
    ids = [str(i) for i in ids]
    return ", ".join(ids[:limit]) + (" …" if len(ids) > limit else "")


def sphericity_text(result) -> str:
    """Return the Greenhouse–Geisser and Huynh–Feldt corrections of a repeated-measures
    result (``epsilon_gg``, ``pvalue_gg``, ``epsilon_hf``, ``pvalue_hf``) for its APA
    line, where Mauchly's test rejected sphericity; "" otherwise."""
    if not (_finite(result.mauchly_pvalue) and result.mauchly_pvalue < 0.05):
        return ""
    return (
        f" (Greenhouse–Geisser ε = {result.epsilon_gg:.2f}, {format_p(result.pvalue_gg)}; "
        f"Huynh–Feldt ε = {result.epsilon_hf:.2f}, {format_p(result.pvalue_hf)})"
    )


def _finite(*values: float | None) -> bool:
    return all(v is not None and math.isfinite(v) for v in values)


def ci_text(ci: tuple[float, float], digits: int = 2) -> str:
    """Format a 95 % CI as "95 % CI a to b", or say it was not computed (n < 2)."""
    if not _finite(*ci):
        return "95 % CI not computed"
    low, high = (f"{v:.{digits}f}".replace(f"-{0:.{digits}f}", f"{0:.{digits}f}") for v in ci)
    return f"95 % CI {low} to {high}"


def _df(value: float) -> str:
    return f"{value:g}" if float(value).is_integer() else f"{value:.2f}"


@dataclasses.dataclass(frozen=True)
class PairComparison(Result):
    """Exact binomial test of one unordered pair (opposite orders tallied together).

    ``statistic`` is a's share of the decisive judgements; ties ("none") are
    excluded from the test, or split when the analysis was asked to.
    """

    a: str
    b: str
    a_wins: int
    b_wins: int
    ties: int
    nobs: int
    statistic: float
    pvalue: float
    pvalue_one_sided_majority: float
    majority: str | None
    pvalue_adjusted: float
    ci: tuple[float, float]
    item: str | None = None

    def apa(self) -> str:
        return (
            f"{self.a} vs {self.b}: {self.a_wins}/{self.nobs} "
            f"({100 * self.statistic:.1f} %), exact binomial {format_p(self.pvalue)} two-sided, "
            f"{format_p(self.pvalue_one_sided_majority)} one-sided"
        )


@dataclasses.dataclass(frozen=True)
class ConditionRate(Result):
    """How often one condition was chosen: per appearance and as a share of choices."""

    condition: str
    shown: int
    chosen: int
    win_rate: float
    share: float
    mean_participant_rate: float
    sem: float
    nobs: int


@dataclasses.dataclass(frozen=True)
class RmAnovaResult(Result):
    """One-way repeated-measures ANOVA with sphericity test and correction.

    ``pvalue_gg`` uses the Greenhouse–Geisser epsilon, ``pvalue_hf`` the Huynh–Feldt one;
    ``eta_p2`` is partial η². With two levels there is no sphericity test (Mauchly's W
    and its p are NaN).
    """

    statistic: float
    df_num: float
    df_den: float
    pvalue: float
    epsilon_gg: float
    pvalue_gg: float
    eta_p2: float
    mauchly_w: float
    mauchly_pvalue: float
    nobs: int
    levels: tuple[str, ...]
    notes: tuple[str, ...] = ()
    epsilon_hf: float = float("nan")
    pvalue_hf: float = float("nan")

    def apa(self) -> str:
        if not math.isfinite(self.statistic):
            return "F not computed: " + (self.notes[-1] if self.notes else "undefined")
        text = (
            f"F({_df(self.df_num)}, {_df(self.df_den)}) = {self.statistic:.2f}, "
            f"{format_p(self.pvalue)}, η²p = {proportion_text(self.eta_p2)}"
        )
        return text + sphericity_text(self)


@dataclasses.dataclass(frozen=True)
class PairedTTest(Result):
    """Paired t-test of a − b with Cohen's d_z and a CI of the mean difference."""

    a: str
    b: str
    statistic: float
    df: int
    pvalue: float
    pvalue_adjusted: float
    mean_difference: float
    ci: tuple[float, float]
    dz: float
    nobs: int
    # Exact 95 % CI of d_z (noncentral t; analysis.within.dz_interval).
    dz_ci: tuple[float, float] = (float("nan"), float("nan"))

    def apa(self) -> str:
        if not _finite(self.statistic):
            return f"{self.a} vs {self.b}: t not computed (n = {self.nobs}, or no variation)"
        return (
            f"{self.a} vs {self.b}: M_diff = {_two(self.mean_difference)} ({ci_text(self.ci)}), "
            f"t({self.df}) = {self.statistic:.2f}, "
            f"{format_p(self.pvalue)} ({format_p(self.pvalue_adjusted).replace('p', 'p_adj', 1)}),"
            f" d_z = {_two(self.dz)}"
            + (f" [{_two(self.dz_ci[0])}, {_two(self.dz_ci[1])}]" if _finite(self.dz_ci[0]) else "")
        )


@dataclasses.dataclass(frozen=True)
class FriedmanResult(Result):
    """Friedman test over conditions, with Kendall's W as the effect size."""

    statistic: float
    df: int
    pvalue: float
    kendall_w: float
    nobs: int

    def apa(self) -> str:
        return (
            f"χ²({self.df}) = {self.statistic:.2f}, {format_p(self.pvalue)}, "
            f"W = {_two(self.kendall_w)}"
        )


# How a Wilcoxon p was found (R's wilcox.test defaults; analysis.within.wilcoxon_test).
EXACT = "exact"
APPROXIMATE = "normal approximation, continuity-corrected"


@dataclasses.dataclass(frozen=True)
class WilcoxonTest(Result):
    """Wilcoxon signed-rank test of a − b as R's ``wilcox.test`` (paired): *statistic* is
    R's V, the positive differences' rank sum; *method* how p was found (exact, or the
    normal approximation with continuity correction); effect size the rank-biserial r."""

    a: str
    b: str
    statistic: float
    pvalue: float
    pvalue_adjusted: float
    rank_biserial: float
    nobs: int
    method: str = ""
    # Why V was not computed, when it was not.
    note: str = ""

    def apa(self) -> str:
        if not _finite(self.statistic):
            why = self.note or "needs 2 or more"
            return f"{self.a} vs {self.b}: V not computed (n = {self.nobs}; {why})"
        return (
            f"{self.a} vs {self.b}: V = {self.statistic:g}, {format_p(self.pvalue)}"
            f"{f' ({self.method})' if self.method else ''} "
            f"({format_p(self.pvalue_adjusted).replace('p', 'p_adj', 1)}), "
            f"r = {_two(self.rank_biserial)}, n = {self.nobs}"
        )


@dataclasses.dataclass(frozen=True)
class Strength(Result):
    """One condition's Bradley–Terry log-worth relative to the reference condition."""

    condition: str
    log_worth: float
    se: float
    ci: tuple[float, float]
    worth: float


@dataclasses.dataclass(frozen=True)
class BradleyTerryResult(Result):
    """Bradley–Terry model fitted by logistic regression; strengths with Wald 95 % CIs."""

    reference: str
    strengths: tuple[Strength, ...]
    nobs: int
    log_likelihood: float
    # Why no strength could be estimated ("" when they were): then strengths is empty.
    not_estimable: str = ""


@dataclasses.dataclass(frozen=True)
class PositionBias(Result):
    """Whether Clip 1 was chosen more or less than half the time (two-sided binomial)."""

    clip1: int
    clip2: int
    nobs: int
    statistic: float
    pvalue: float
    ci: tuple[float, float]

    def apa(self) -> str:
        return (
            f"Clip 1 chosen in {self.clip1} of {self.nobs} decisive judgements "
            f"({100 * self.statistic:.1f} %), exact binomial {format_p(self.pvalue)}"
        )


@dataclasses.dataclass(frozen=True)
class PairwiseAnalysis(Result):
    """Everything computed from the pairwise (and comparative) judgements of a study."""

    conditions: tuple[ConditionRate, ...]
    pairs: tuple[PairComparison, ...]
    items: tuple[PairComparison, ...]
    rm_anova: RmAnovaResult | None
    posthoc: tuple[PairedTTest, ...]
    friedman: FriedmanResult | None
    wilcoxon: tuple[WilcoxonTest, ...]
    bradley_terry: BradleyTerryResult | None
    position_bias: PositionBias | None
    ties: int
    judgements: int
    participants: int
    tie_handling: str
    correction: str
    notes: tuple[str, ...] = ()


@dataclasses.dataclass(frozen=True)
class ComparativePreference(Result):
    """Mean comparative-scale preference for *a* over *b* (scale points), signed-rank tested.

    *statistic* is the Wilcoxon V (R's) of the participants' mean preferences against 0,
    its p found by *method*;
    *ci* the t-based 95 % CI of their mean; *nobs* participants; *judgements* answers.
    """

    a: str
    b: str
    statistic: float
    pvalue: float
    pvalue_adjusted: float
    mean_preference: float
    ci: tuple[float, float]
    rank_biserial: float
    nobs: int
    judgements: int
    points: int = 5
    method: str = ""

    def with_adjusted(self, pvalue: float) -> "ComparativePreference":
        """Return a copy with its p-value corrected for the pairs tested."""
        return dataclasses.replace(self, pvalue_adjusted=float(pvalue))

    def apa(self) -> str:
        text = (
            f"{self.a} vs {self.b}: M = {_two(self.mean_preference)} points toward {self.a} "
            f"({ci_text(self.ci)}), "
        )
        if not _finite(self.statistic):
            return text + f"V not computed (n = {self.nobs}; needs 2 or more)"
        return text + (
            f"V = {self.statistic:g}, {format_p(self.pvalue)}"
            f"{f' ({self.method})' if self.method else ''}, "
            f"r = {_two(self.rank_biserial)}, n = {self.nobs}"
        )


@dataclasses.dataclass(frozen=True)
class ExclusionReport(Result):
    """Who was left out before analysis, and why (a participant counts once per reason)."""

    participants_total: int
    participants_included: int
    excluded_by_reason: dict[str, int]
    rules: dict[str, Any]
    # Participant id → the reasons they were excluded for.
    excluded_participants: dict[str, list[str]] = dataclasses.field(default_factory=dict)
