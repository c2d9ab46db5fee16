"""Frozen results that describe and compare conditions on ratings and intelligibility.

Per item (a question's ratings, typed answers' accuracy) and per condition across items
on participants' means; each comparison is a paired t-test with a Wilcoxon signed-rank
test (:mod:`analysis.within`). Like :mod:`analysis.results`, every one has ``to_dict()``
and, where a test is involved, ``apa()``.
"""

import dataclasses

from analysis.results import PairedTTest, Result, WilcoxonTest, few_named


@dataclasses.dataclass(frozen=True)
class RatingSummary(Result):
    """Descriptive statistics of one question's ratings of one item in one condition."""

    item: str
    condition: str
    question: str
    n: int
    median: float
    q1: float
    q3: float
    mean: float
    sd: float
    pct_ge3: float
    pct_ge4: float


@dataclasses.dataclass(frozen=True)
class PairedComparison(Result):
    """Two conditions compared by a paired t-test and a Wilcoxon signed-rank test."""

    a: str
    b: str
    nobs: int
    wilcoxon: WilcoxonTest
    ttest: PairedTTest
    # Participants with an answer in only one of the two conditions: not in the tests.
    left_out: tuple[str, ...] = ()

    def apa(self) -> str:
        text = f"{self.ttest.apa()}; {self.wilcoxon.apa()}"
        if self.left_out:
            text += (
                f" ({len(self.left_out)} participant{'s' if len(self.left_out) > 1 else ''} "
                f"with only one of the two conditions left out: {few_named(self.left_out)})"
            )
        return text


@dataclasses.dataclass(frozen=True)
class RatingComparison(PairedComparison):
    """Paired comparison of two conditions' ratings of one item on one question."""

    item: str = ""
    question: str = ""

    def apa(self) -> str:
        return f"{self.item}, {self.question}: {super().apa()}"


@dataclasses.dataclass(frozen=True)
class ConditionSummary(Result):
    """One condition on one measure across items: participants' means, then their mean.

    *measure* is a rating question's key or ``"accuracy"`` (intelligibility); *n* the
    answers, *nobs* the participants; *sd*, *sem* and the t-based *ci* are over the
    participants' means, the median and quartiles over the answers.
    """

    measure: str
    condition: str
    n: int
    nobs: int
    items: int
    mean: float
    sd: float
    sem: float
    ci: tuple[float, float]
    median: float
    q1: float
    q3: float


@dataclasses.dataclass(frozen=True)
class ConditionComparison(PairedComparison):
    """Two conditions compared on participants' means across items (paired tests)."""

    measure: str = ""

    def apa(self) -> str:
        return f"{self.measure}: {super().apa()}"


@dataclasses.dataclass(frozen=True)
class IntelligibilityScore(Result):
    """Mean word-level accuracy of typed answers for one condition and item."""

    condition: str
    item: str
    n: int
    mean_accuracy: float
    sem: float
