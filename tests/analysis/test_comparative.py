"""Test the comparative-scale analysis (seed 001 §5.2.3) against a hand-computed case."""

import numpy as np
import pandas as pd
import pytest
from scipy import stats

from analysis.comparative import compare_preferences, preferences
from analysis.outputs import tables
from analysis.report import ReportOptions, build_report, results_json
from analysis.tidy import check_responses
from tests.analysis.published import COLUMNS, _row


def _answer(participant, clip1, clip2, rating, item="P1", flags=""):
    return _row(
        participant=participant,
        study="transitions",
        block="comparisons",
        trial=f"{item}-{clip1}-{clip2}",
        item=item,
        kind="comparative",
        condition_a=clip1,
        condition_b=clip2,
        rating=str(rating),
        question="compare",
        rt_ms="2000",
        flags=flags,
    )


def _frame(rows) -> pd.DataFrame:
    return check_responses(pd.DataFrame(rows, columns=COLUMNS))


HAND = [
    # p1: A a lot better as clip 1 (+2 for A); B a little worse as clip 1 (+1 for A) → 1.5
    _answer("p1", "A", "B", 1),
    _answer("p1", "B", "A", 4, item="P2"),
    # p2: A a little better as clip 1 → +1
    _answer("p2", "A", "B", 2),
    # p3: B a little better as clip 1 → −1 for A
    _answer("p3", "B", "A", 2),
    # An attention check says nothing about the conditions.
    _answer("p3", "A", "B", 5, flags="attention_check"),
]


def test_preferences_point_toward_clip_1():
    data = preferences(_frame(HAND))
    assert list(data["preference"]) == [2.0, -1.0, 1.0, 1.0]


def test_mean_preference_ci_and_signed_rank_by_hand():
    (result,) = compare_preferences(_frame(HAND))
    values = np.array([1.5, 1.0, -1.0])  # per participant, toward A
    assert (result.a, result.b, result.nobs, result.judgements) == ("A", "B", 3, 4)
    assert result.mean_preference == pytest.approx(0.5)
    half = stats.t.ppf(0.975, 2) * values.std(ddof=1) / np.sqrt(3)
    assert result.ci == pytest.approx((0.5 - half, 0.5 + half))
    # |1.5| ranks 3, |1| and |−1| share rank 1.5: V = W⁺ = 4.5 (R's statistic), W⁻ = 1.5.
    assert result.statistic == pytest.approx(4.5)
    assert result.rank_biserial == pytest.approx((4.5 - 1.5) / 6)
    # A tie: R's wilcox.test takes the normal approximation with continuity correction.
    approximate = stats.wilcoxon(values, correction=True, method="approx").pvalue
    assert result.pvalue == pytest.approx(approximate)
    assert result.method == "normal approximation, continuity-corrected"
    assert "points toward A" in result.apa()


def test_order_of_conditions_sets_the_sign_and_holm_corrects():
    rows = HAND + [_answer(f"q{k}", "C", "A", 1 + k % 2) for k in range(6)]
    results = compare_preferences(_frame(rows), conditions=["B", "A", "C"])
    first = next(r for r in results if (r.a, r.b) == ("B", "A"))
    assert first.mean_preference == pytest.approx(-0.5)
    second = next(r for r in results if (r.a, r.b) == ("A", "C"))
    assert second.mean_preference < 0  # C was clip 1 and better every time
    raw = sorted(r.pvalue for r in results)
    assert sorted(r.pvalue_adjusted for r in results)[0] == pytest.approx(min(1, 2 * raw[0]))
    assert all((r.a, r.b) != ("B", "C") for r in results)  # a pair never shown is left out


def test_report_carries_the_comparative_table():
    report = build_report(_frame(HAND), ReportOptions(mixed_models=False))
    data = results_json(report)
    assert data["comparative"][0]["mean_preference"] == pytest.approx(0.5)
    assert "apa" in data["comparative"][0]
    table = tables(report, data)["comparative"]
    assert list(table.columns[:3]) == ["a", "b", "mean_preference_a"]
