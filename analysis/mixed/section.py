"""Fit the report's mixed models: the pairwise model and each rated question's models."""

from collections.abc import Sequence

import numpy as np
import pandas as pd

from analysis.mixed.linear import linear_mixed
from analysis.mixed.ordinal import ordinal_mixed
from analysis.mixed.pairwise import mixed_bradley_terry
from analysis.mixed.results import MixedModels
from analysis.tidy import CONTINUOUS, TidyFormatError, analysed, rating_scale

# Fewer participants than this leave random-effect variances unestimable in practice.
MIN_PARTICIPANTS = 5


def fit_mixed_models(
    frame: pd.DataFrame,
    conditions: Sequence[str] | None = None,
    *,
    ties: str = "exclude",
    correction: str = "holm",
    comparative_points: int = 5,
) -> MixedModels:
    """Fit every mixed model the data allow; say in ``skipped`` why any was left out."""
    skipped: list[str] = []
    pairwise = None
    rows = frame[analysed(frame)]
    choice_rows = rows[rows["kind"].isin(("pairwise", "comparative"))]
    if not choice_rows.empty:
        if choice_rows["participant"].nunique() < MIN_PARTICIPANTS:
            skipped.append(
                f"pairwise: {choice_rows['participant'].nunique()} participants; "
                f"mixed models need at least {MIN_PARTICIPANTS}."
            )
        else:
            try:
                pairwise = mixed_bradley_terry(
                    frame,
                    conditions,
                    ties=ties,
                    correction=correction,
                    comparative_points=comparative_points,
                )
            except (TidyFormatError, np.linalg.LinAlgError, ValueError, ArithmeticError) as problem:
                skipped.append(f"pairwise: {problem}")
    ordinal, linear = [], []
    ratings = rows[rows["kind"].eq("rating") & rows["rating"].notna()]
    for question in sorted(set(ratings["question"]) - {""}):
        asked = ratings[ratings["question"].eq(question)]
        if asked["participant"].nunique() < MIN_PARTICIPANTS:
            skipped.append(
                f"{question}: {asked['participant'].nunique()} participants; "
                f"mixed models need at least {MIN_PARTICIPANTS}."
            )
            continue
        order = [c for c in conditions or () if c in set(asked["condition_a"])] or None
        try:
            # A continuous scale (a slider) has no points for thresholds: linear only.
            if rating_scale(frame, question) != CONTINUOUS:
                ordinal.append(ordinal_mixed(frame, question, order, correction=correction))
            linear.append(linear_mixed(frame, question, order, correction=correction))
        except (TidyFormatError, np.linalg.LinAlgError, ValueError, ArithmeticError) as problem:
            skipped.append(f"{question}: {problem}")
    return MixedModels(
        pairwise=pairwise, ordinal=tuple(ordinal), linear=tuple(linear), skipped=tuple(skipped)
    )
