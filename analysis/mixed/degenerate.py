"""Say why data cannot support a mixed model, before a fit turns them into numbers.

A response with no variance, or one that the conditions determine exactly, leaves a
model nothing to estimate an error (or, for choices and ordered ratings, a finite odds
ratio) from: the fit would return SEs of 0, z in the quadrillions or p = 1 that look like
results. A fixed-effect column that repeats others is dropped, as lme4 does ("fixed-effect
model matrix is rank deficient so dropping 1 column / coefficient").
"""

import dataclasses

import numpy as np

from analysis.mixed.problem import MixedProblem
from analysis.tidy import TidyFormatError

# A column is aliased when its residual on the columns before it is this small
# relative to its own size (lme4's rankMatrix tolerance).
RANK_TOL = 1e-7


def check_response(
    what: str, values: np.ndarray, groups: np.ndarray, labels: np.ndarray, noun: str
) -> None:
    """Refuse *values* that do not vary, or that *groups* (one code per row) determine.

    *labels* name each row's group (a condition) for the message; *noun* names the
    values ("rating", "choice").
    """
    values = np.asarray(values, dtype=float)
    if np.ptp(values) == 0:
        raise TidyFormatError(
            f"{what}: every {noun} is {values[0]:g}, so there is no variation to model; "
            "report the value, not a test."
        )
    within = [np.ptp(values[groups == g]) for g in np.unique(groups)]
    if max(within) == 0:
        shown = {}
        for label, value in zip(labels, values, strict=True):
            shown.setdefault(str(label), f"{value:g}")
        listed = "; ".join(f"{label}: every {noun} {value}" for label, value in shown.items())
        raise TidyFormatError(
            f"{what}: the {noun}s are fully determined by condition ({listed}), so no "
            "variation is left to estimate an error from and the difference is infinite "
            "on the model's scale; report the values, not a test."
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
