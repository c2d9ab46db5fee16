"""Summarize Likert ratings and compare conditions on them (spec 07 "Ratings")."""

import numpy as np
import pandas as pd

from analysis.conditions import SCORE_COLUMNS
from analysis.summaries import RatingComparison, RatingSummary
from analysis.tidy import analysed
from analysis.within import adjust_comparisons, paired_comparisons

GROUP = ["item", "condition_a", "question"]


def rating_rows(frame: pd.DataFrame) -> pd.DataFrame:
    """Return the rating rows that enter the analysis (no practice or attention checks)."""
    return frame[frame["kind"].eq("rating") & analysed(frame)]


def rating_scores(frame: pd.DataFrame) -> pd.DataFrame:
    """Return the analysed ratings as a long score table (measure: the question's key)."""
    rows = rating_rows(frame)
    return pd.DataFrame(
        {
            "measure": rows["question"].to_numpy(),
            "participant": rows["participant"].to_numpy(),
            "item": rows["item"].to_numpy(),
            "condition": rows["condition_a"].to_numpy(),
            "score": rows["rating"].to_numpy(float),
        },
        columns=list(SCORE_COLUMNS),
    )


def summarize_ratings(frame: pd.DataFrame) -> tuple[RatingSummary, ...]:
    """Describe each item × condition × question: n, median, quartiles, mean, SD, % ≥ 3, % ≥ 4.

    Quartiles use linear interpolation (numpy's default, R type 7). Seed 003 §5.5
    reports "% rated 3 or above" and "% rated 4–5".
    """
    rows = rating_rows(frame)
    if rows.empty:
        return ()
    grouped = rows.groupby(GROUP, sort=True)["rating"]
    table = grouped.agg(
        n="size",
        median="median",
        q1=lambda r: np.percentile(r, 25),
        q3=lambda r: np.percentile(r, 75),
        mean="mean",
        sd=lambda r: r.std(ddof=1) if len(r) > 1 else float("nan"),
        pct_ge3=lambda r: 100 * (r >= 3).mean(),
        pct_ge4=lambda r: 100 * (r >= 4).mean(),
    ).reset_index()
    return tuple(
        RatingSummary(
            item=row.item,
            condition=row.condition_a,
            question=row.question,
            n=int(row.n),
            median=float(row.median),
            q1=float(row.q1),
            q3=float(row.q3),
            mean=float(row.mean),
            sd=float(row.sd),
            pct_ge3=float(row.pct_ge3),
            pct_ge4=float(row.pct_ge4),
        )
        for row in table.itertuples(index=False)
    )


def compare_ratings(frame: pd.DataFrame, correction: str = "holm") -> tuple[RatingComparison, ...]:
    """Compare every two conditions that rated the same item and question, per participant.

    Wilcoxon signed-rank and paired t on participants who rated both (e.g. spine on vs
    off); p-values corrected across all comparisons.
    """
    rows = rating_rows(frame)
    comparisons = []
    for (item, question), group in rows.groupby(["item", "question"], sort=True):
        # A participant's repeated ratings of one cell are averaged.
        wide = group.pivot_table(
            index="participant", columns="condition_a", values="rating", aggfunc="mean"
        )
        comparisons += paired_comparisons(wide, RatingComparison, item=item, question=question)
    return adjust_comparisons(comparisons, correction)
