"""Analyse comparative-scale answers as preferences between conditions (seed 001 §5.2.3).

A comparative scale (Video A a lot better … Video B a lot better) says by how much one
clip beats the other. Each answer becomes a preference in scale points for one
condition of its pair: the midpoint is 0 and each step toward a clip counts one point
for that clip's condition, whichever side it was shown on. Per pair of conditions, each
participant's preferences are averaged; the mean over participants has a t-based 95 %
CI, and a Wilcoxon signed-rank test asks whether the median preference is zero
(effect size: the matched rank-biserial r), corrected across pairs.
"""

from collections.abc import Sequence
from itertools import combinations

import numpy as np
import pandas as pd

from analysis.results import ComparativePreference
from analysis.tidy import analysed
from analysis.within import adjust, mean_ci, wilcoxon_test


def preferences(frame: pd.DataFrame, points: int = 5) -> pd.DataFrame:
    """Return one row per comparative answer: participant, item, clip conditions, preference.

    ``preference`` is in scale points toward ``clip1`` (positive: clip 1 was better).
    Practice and attention-check rows are left out.
    """
    rows = frame[frame["kind"].eq("comparative") & analysed(frame)]
    rating = pd.to_numeric(rows["rating"], errors="coerce")
    midpoint = (1 + points) / 2
    return pd.DataFrame(
        {
            "participant": rows["participant"].to_numpy(),
            "item": rows["item"].to_numpy(),
            "clip1": rows["condition_a"].to_numpy(),
            "clip2": rows["condition_b"].to_numpy(),
            "preference": (midpoint - rating).to_numpy(),
        }
    ).dropna(subset=["preference"])


def compare_preferences(
    frame: pd.DataFrame,
    conditions: Sequence[str] | None = None,
    points: int = 5,
    correction: str = "holm",
) -> tuple[ComparativePreference, ...]:
    """Return the mean preference and signed-rank test of every pair of conditions shown.

    Pairs follow *conditions*' order (else alphabetical): ``a`` is the earlier, and a
    positive mean favours ``a``.
    """
    data = preferences(frame, points)
    if data.empty:
        return ()
    order = list(conditions) if conditions else sorted(set(data["clip1"]) | set(data["clip2"]))
    results = []
    for a, b in combinations(order, 2):
        forward = data["clip1"].eq(a) & data["clip2"].eq(b)
        backward = data["clip1"].eq(b) & data["clip2"].eq(a)
        pair = data[forward | backward]
        if pair.empty:
            continue
        toward_a = np.where(forward[forward | backward], pair["preference"], -pair["preference"])
        per_participant = (
            pd.Series(toward_a, index=pair["participant"].to_numpy()).groupby(level=0).mean()
        )
        values = per_participant.to_numpy()
        n = len(values)
        mean = float(values.mean())
        # No spread, no interval: all participants' preferences alike.
        ci = mean_ci(values) if n > 1 and values.std(ddof=1) > 0 else (np.nan, np.nan)
        test = wilcoxon_test(values, np.zeros(n), (a, b))
        results.append(
            ComparativePreference(
                a=a,
                b=b,
                statistic=test.statistic,
                pvalue=test.pvalue,
                pvalue_adjusted=test.pvalue,
                mean_preference=mean,
                ci=(float(ci[0]), float(ci[1])),
                rank_biserial=test.rank_biserial,
                nobs=n,
                judgements=len(pair),
                points=points,
                method=test.method,
            )
        )
    adjusted = adjust([r.pvalue for r in results], correction)
    return tuple(r.with_adjusted(p) for r, p in zip(results, adjusted, strict=True))
