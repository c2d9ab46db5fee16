"""Say why data cannot support a mixed model, before a fit turns them into numbers.

A response with no variance, or one that the conditions determine exactly, leaves a
model nothing to estimate an error (or, for choices and ordered ratings, a finite odds
ratio) from: the fit would return SEs of 0, z in the quadrillions or p = 1 that look like
results. A fixed-effect column that repeats others is dropped, as lme4 does ("fixed-effect
model matrix is rank deficient so dropping 1 column / coefficient").
"""

import dataclasses

import numpy as np
import pandas as pd

from analysis.mixed.problem import MixedProblem
from analysis.tidy import TidyFormatError

# A column is aliased when its residual on the columns before it is this small
# relative to its own size (lme4's rankMatrix tolerance).
RANK_TOL = 1e-7


def check_ratings(question: str, data: pd.DataFrame) -> None:
    """Refuse one question's ratings (rows with condition and rating) that do not vary,
    or that the condition, or the participant, determines."""
    values = data["rating"].to_numpy(dtype=float)
    what = f"question {question!r}"
    if np.ptp(values) == 0:
        raise TidyFormatError(
            f"{what}: every rating is {values[0]:g}, so there is no variation to model; "
            "report the value, not a test."
        )
    spread = data.groupby("condition", sort=False)["rating"].agg(["min", "max"])
    if (spread["min"] == spread["max"]).all():
        listed = "; ".join(f"{c}: every rating {row['min']:g}" for c, row in spread.iterrows())
        raise TidyFormatError(
            f"{what}: the ratings are fully determined by condition ({listed}), so no "
            "variation is left to estimate an error from and the difference is infinite "
            "on the model's scale; report the values, not a test."
        )
    if "participant" in data.columns:
        each = data.groupby("participant", sort=False)["rating"].agg(["min", "max"])
        if (each["min"] == each["max"]).all():
            raise TidyFormatError(
                f"{what}: every participant gave one rating to every clip, so the "
                "participants determine the ratings and nothing is left to estimate an "
                "error or a condition effect within participants from; report the "
                "values, not a test."
            )


def full_rank(problem: MixedProblem) -> tuple[MixedProblem, tuple[str, ...]]:
    """Return *problem* without fixed-effect columns that repeat earlier ones, and their names.

    Columns are kept in order, each if it is not a linear combination of those kept
    before it (as R's ``qr`` keeps the earlier of two aliased columns).
    """
    X = np.asarray(problem.X, dtype=float)
    keep: list[int] = []
    for j in range(X.shape[1]):
        column = X[:, j]
        size = np.linalg.norm(column)
        if size == 0:
            continue
        if keep:
            basis = X[:, keep]
            coefficients = np.linalg.lstsq(basis, column, rcond=None)[0]
            if np.linalg.norm(column - basis @ coefficients) <= RANK_TOL * size:
                continue
        keep.append(j)
    if len(keep) == X.shape[1]:
        return problem, ()
    dropped = tuple(n for j, n in enumerate(problem.fixed_names) if j not in keep)
    reduced = dataclasses.replace(
        problem, X=X[:, keep], fixed_names=tuple(problem.fixed_names[j] for j in keep)
    )
    return reduced, dropped


def dropped_message(dropped: tuple[str, ...]) -> str:
    """Return lme4's message for dropped columns, with their names."""
    count = len(dropped)
    return (
        f"fixed-effect model matrix is rank deficient so dropping {count} "
        f"column{'s' if count > 1 else ''} / coefficient{'s' if count > 1 else ''} "
        f"({', '.join(dropped)}): {'they repeat' if count > 1 else 'it repeats'} other columns"
    )
