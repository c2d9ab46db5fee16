"""Analyse forced-choice and comparative judgements between conditions (spec 07 "Pairwise")."""

import dataclasses
from collections.abc import Sequence
from itertools import combinations

import numpy as np
import pandas as pd
from scipy import stats

from analysis.anova import rm_anova
from analysis.bradley_terry import bradley_terry
from analysis.results import ConditionRate, PairComparison, PairwiseAnalysis, PositionBias
from analysis.tidy import NO_DIFFERENCE, analysed
from analysis.within import adjust, friedman, paired_ttests, wilcoxon_tests

TIE_HANDLING = ("exclude", "split")


def judgements(frame: pd.DataFrame, comparative_points: int = 5) -> pd.DataFrame:
    """Return one row per pairwise judgement: participant, item, clip1, clip2, chosen, position.

    Practice and attention-check rows are left out. A comparative-scale answer counts as
    a choice of the clip it favours, and as "none" at the scale's midpoint.
    ``position`` is 1 or 2 for the chosen clip, 0 for "none".
    """
    rows = frame[frame["kind"].isin(("pairwise", "comparative")) & analysed(frame)]
    chosen = rows["chosen"].copy()
    comparative = rows["kind"].eq("comparative")
    if comparative.any():
        midpoint = (1 + comparative_points) / 2
        rating = rows.loc[comparative, "rating"]
        chosen.loc[comparative] = np.where(
            rating < midpoint,
            rows.loc[comparative, "condition_a"],
            np.where(rating > midpoint, rows.loc[comparative, "condition_b"], NO_DIFFERENCE),
        )
    position = np.select(
        [chosen.eq(rows["condition_a"]), chosen.eq(rows["condition_b"])], [1, 2], default=0
    )
    return pd.DataFrame(
        {
            "participant": rows["participant"].to_numpy(),
            "item": rows["item"].to_numpy(),
            "clip1": rows["condition_a"].to_numpy(),
            "clip2": rows["condition_b"].to_numpy(),
            "chosen": chosen.to_numpy(),
            "position": position,
        }
    )


def condition_order(data: pd.DataFrame, conditions: Sequence[str] | None = None) -> list[str]:
    """Return the conditions in report order: as given, else alphabetical."""
    if conditions:
        return list(conditions)
    return sorted(set(data["clip1"]) | set(data["clip2"]))


def tally(data: pd.DataFrame, order: Sequence[str], by: Sequence[str] = ()) -> pd.DataFrame:
    """Count wins per unordered pair (a before b in *order*), both orders tallied together."""
    rank = {condition: index for index, condition in enumerate(order)}
    first_is_a = data["clip1"].map(rank) < data["clip2"].map(rank)
    a = np.where(first_is_a, data["clip1"], data["clip2"])
    b = np.where(first_is_a, data["clip2"], data["clip1"])
    counted = data.assign(
        a=a,
        b=b,
        a_wins=(data["chosen"] == a).astype(int),
        b_wins=(data["chosen"] == b).astype(int),
        ties=(data["chosen"] == NO_DIFFERENCE).astype(int),
    )
    keys = [*by, "a", "b"]
    return counted.groupby(keys, sort=False)[["a_wins", "b_wins", "ties"]].sum().reset_index()


def binomial_pair(
    a: str, b: str, a_wins: int, b_wins: int, ties: int, tie_handling: str, item: str | None
) -> PairComparison:
    """Test one pair exactly: two-sided, and one-sided in the direction of the majority."""
    if tie_handling == "split":
        # Half the ties to each side; an odd tie left over cannot be split and is dropped.
        a_wins, b_wins = a_wins + ties // 2, b_wins + ties // 2
    n = a_wins + b_wins
    if n == 0:
        nan = float("nan")
        return PairComparison(
            a, b, a_wins, b_wins, ties, 0, nan, nan, nan, None, nan, (nan, nan), item
        )
    test = stats.binomtest(a_wins, n, 0.5)
    majority_wins = max(a_wins, b_wins)
    one_sided = stats.binomtest(majority_wins, n, 0.5, alternative="greater").pvalue
    majority = a if a_wins > b_wins else b if b_wins > a_wins else None
    interval = test.proportion_ci(0.95, method="exact")
    return PairComparison(
        a=a,
        b=b,
        a_wins=int(a_wins),
        b_wins=int(b_wins),
        ties=int(ties),
        nobs=int(n),
        statistic=a_wins / n,
        pvalue=float(test.pvalue),
        pvalue_one_sided_majority=float(one_sided),
        majority=majority,
        pvalue_adjusted=float(test.pvalue),
        ci=(float(interval.low), float(interval.high)),
        item=item,
    )


def _pair_tests(counts: pd.DataFrame, tie_handling: str, correction: str, item_column: bool):
    tests = [
        binomial_pair(
            row.a,
            row.b,
            int(row.a_wins),
            int(row.b_wins),
            int(row.ties),
            tie_handling,
            row.item if item_column else None,
        )
        for row in counts.itertuples(index=False)
    ]
    adjusted = adjust([t.pvalue for t in tests], correction)
    return tuple(
        dataclasses.replace(t, pvalue_adjusted=float(p))
        for t, p in zip(tests, adjusted, strict=True)
    )


def participant_rates(data: pd.DataFrame, order: Sequence[str]) -> pd.DataFrame:
    """Return each participant's win rate per condition (chosen / shown), participants × order."""
    shown = pd.concat(
        [
            data[["participant", "clip1"]].set_axis(["participant", "c"], axis=1),
            data[["participant", "clip2"]].set_axis(["participant", "c"], axis=1),
        ]
    )
    shown_counts = shown.groupby(["participant", "c"]).size().unstack(fill_value=0)
    chosen_counts = (
        data[data["chosen"] != NO_DIFFERENCE]
        .groupby(["participant", "chosen"])
        .size()
        .unstack(fill_value=0)
    )
    shown_counts = shown_counts.reindex(columns=list(order), fill_value=0)
    chosen_counts = chosen_counts.reindex(
        index=shown_counts.index, columns=list(order), fill_value=0
    )
    rates = chosen_counts / shown_counts.where(shown_counts > 0)
    rates.columns.name = None
    return rates


def _condition_rates(data: pd.DataFrame, order: Sequence[str], rates: pd.DataFrame):
    shown = pd.concat([data["clip1"], data["clip2"]]).value_counts()
    chosen = data.loc[data["chosen"] != NO_DIFFERENCE, "chosen"].value_counts()
    decisive = int(chosen.sum())
    result = []
    for condition in order:
        per_participant = rates[condition].dropna()
        n = len(per_participant)
        result.append(
            ConditionRate(
                condition=condition,
                shown=int(shown.get(condition, 0)),
                chosen=int(chosen.get(condition, 0)),
                win_rate=float(chosen.get(condition, 0) / shown[condition])
                if shown.get(condition, 0)
                else float("nan"),
                share=float(chosen.get(condition, 0) / decisive) if decisive else float("nan"),
                mean_participant_rate=float(per_participant.mean()) if n else float("nan"),
                sem=float(per_participant.std(ddof=1) / np.sqrt(n)) if n > 1 else float("nan"),
                nobs=n,
            )
        )
    return tuple(result)


def position_bias(data: pd.DataFrame) -> PositionBias | None:
    """Test whether Clip 1 and Clip 2 were chosen equally often (ties left out)."""
    clip1 = int((data["position"] == 1).sum())
    clip2 = int((data["position"] == 2).sum())
    if clip1 + clip2 == 0:
        return None
    test = stats.binomtest(clip1, clip1 + clip2, 0.5)
    interval = test.proportion_ci(0.95, method="exact")
    return PositionBias(
        clip1=clip1,
        clip2=clip2,
        nobs=clip1 + clip2,
        statistic=clip1 / (clip1 + clip2),
        pvalue=float(test.pvalue),
        ci=(float(interval.low), float(interval.high)),
    )


def _repeated_measures(rates: pd.DataFrame, order, correction: str, notes: list[str]):
    """Return the repeated-measures tests of participants' win rates (ANOVA, paired t,
    Wilcoxon, Friedman), None where they cannot run; say why in *notes*."""
    complete = rates.dropna()
    if len(complete) < len(rates):
        notes.append(
            f"{len(rates) - len(complete)} participant(s) did not see every condition and are "
            "left out of the repeated-measures tests."
        )
    if len(complete) < 2 or len(order) < 2:
        notes.append("Fewer than two complete participants: no repeated-measures tests.")
        return None, None, None, None
    fried = friedman(complete) if len(order) >= 3 else None
    return (
        rm_anova(complete),
        paired_ttests(complete, correction),
        fried,
        wilcoxon_tests(complete, correction),
    )


def analyze_pairwise(
    frame: pd.DataFrame,
    *,
    conditions: Sequence[str] | None = None,
    tie_handling: str = "exclude",
    correction: str = "holm",
    comparative_points: int = 5,
) -> PairwiseAnalysis | None:
    """Run every pairwise analysis of spec 07 on a checked tidy table.

    Return None when the table has no pairwise judgements.
    """
    if tie_handling not in TIE_HANDLING:
        raise ValueError(f"tie_handling must be one of {', '.join(TIE_HANDLING)}.")
    data = judgements(frame, comparative_points)
    if data.empty:
        return None
    order = condition_order(data, conditions)
    notes: list[str] = []

    pair_counts = tally(data, order)
    pair_counts = (
        pair_counts.set_index(["a", "b"])
        .reindex([(a, b) for a, b in combinations(order, 2)], fill_value=0)
        .reset_index()
    )
    pairs = _pair_tests(pair_counts, tie_handling, correction, item_column=False)
    rank = {condition: index for index, condition in enumerate(order)}
    item_counts = tally(data, order, by=["item"])
    item_counts = item_counts.iloc[
        np.lexsort((item_counts["b"].map(rank), item_counts["a"].map(rank), item_counts["item"]))
    ]
    items = _pair_tests(item_counts, tie_handling, correction, item_column=True)
    rates = participant_rates(data, order)
    rm, post, fried, wil = _repeated_measures(rates, order, correction, notes)
    bt = None
    if len(order) >= 2 and int(pair_counts[["a_wins", "b_wins"]].to_numpy().sum()) > 0:
        bt = bradley_terry(pair_counts, order)
    return PairwiseAnalysis(
        conditions=_condition_rates(data, order, rates),
        pairs=pairs,
        items=items,
        rm_anova=rm,
        posthoc=post or (),
        friedman=fried,
        wilcoxon=wil or (),
        bradley_terry=bt,
        position_bias=position_bias(data),
        ties=int((data["chosen"] == NO_DIFFERENCE).sum()),
        judgements=len(data),
        participants=int(data["participant"].nunique()),
        tie_handling=tie_handling,
        correction=correction,
        notes=tuple(notes),
    )
