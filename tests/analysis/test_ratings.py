"""Test Likert summaries and on/off comparisons (spec 07 "Ratings")."""

import numpy as np
import pandas as pd
import pytest

from analysis import check_responses, compare_ratings, summarize_ratings
from tests.analysis.published import COLUMNS


def rating_table(ratings: dict[tuple[str, str, str], list[int]]) -> pd.DataFrame:
    rows = []
    for (item, condition, question), values in ratings.items():
        for participant, value in enumerate(values):
            row = dict.fromkeys(COLUMNS, "")
            row.update(
                participant=f"P{participant}",
                study="spine",
                block="ratings",
                trial=f"rate-{item}",
                item=item,
                kind="rating",
                condition_a=condition,
                question=question,
                rating=str(value),
            )
            rows.append(row)
    return check_responses(pd.DataFrame(rows, columns=COLUMNS))


def test_summary_statistics_by_hand():
    values = [1, 2, 3, 3, 4, 5, 5, 4]
    (summary,) = summarize_ratings(rating_table({("S1", "on", "clarity"): values}))
    assert (summary.item, summary.condition, summary.question, summary.n) == (
        "S1",
        "on",
        "clarity",
        8,
    )
    assert summary.median == 3.5
    assert (summary.q1, summary.q3) == (np.percentile(values, 25), np.percentile(values, 75))
    assert summary.mean == pytest.approx(3.375)
    assert summary.sd == pytest.approx(np.std(values, ddof=1))
    assert summary.pct_ge3 == 75.0  # 6 of 8 rated 3 or above (seed 003 §5.5 wording)
    assert summary.pct_ge4 == 50.0


def test_on_off_comparison_pairs_participants():
    on = [5, 4, 5, 4, 5, 3, 4, 5, 4, 5]
    off = [3, 3, 4, 2, 3, 3, 2, 4, 3, 3]
    comparisons = compare_ratings(
        rating_table({("S2", "on", "naturalness"): on, ("S2", "off", "naturalness"): off})
    )
    (comparison,) = comparisons
    assert (comparison.a, comparison.b, comparison.nobs) == ("off", "on", 10)
    assert comparison.ttest.mean_difference == pytest.approx(np.mean(off) - np.mean(on))
    assert comparison.wilcoxon.pvalue < 0.05 and comparison.wilcoxon.rank_biserial < 0


def test_practice_rows_are_not_summarized():
    table = rating_table({("S1", "on", "clarity"): [4, 4, 4]})
    table.loc[0, "flags"] = "practice"
    (summary,) = summarize_ratings(table)
    assert summary.n == 2


def test_a_table_without_rows_selects_no_ratings_and_warns_of_nothing():
    """Mapping no rows' flags gave a str column, which pandas warned (and pandas 4 will
    refuse) to combine with the kind's mask."""
    import warnings

    from analysis.ratings import rating_rows

    empty = pd.DataFrame({column: pd.Series([], dtype=str) for column in COLUMNS})
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert rating_rows(empty).empty
