"""The crossed designs R simulated and fitted (tests/analysis/reference/crossed.R), as inputs.

Each set's rows become the public APIs' tidy tables, or a :class:`MixedProblem` for the
binary GLMM, which has no tidy-table front end.
"""

import functools
import json

import numpy as np
import pandas as pd

from analysis.mixed import MixedProblem
from analysis.mixed.common import intercepts
from tests.analysis.mixed_data import REFERENCE, pairwise_rows, rating_rows


@functools.cache
def fits() -> dict:
    """Return R's fits: {"software": …, "sets": [one dict per set]}."""
    return json.loads((REFERENCE / "crossed_fits.json").read_text())


@functools.cache
def _within() -> pd.DataFrame:
    return pd.read_csv(REFERENCE / "crossed_within.csv.gz")


@functools.cache
def _pairs() -> pd.DataFrame:
    return pd.read_csv(REFERENCE / "crossed_pairs.csv.gz")


def within(number: int) -> pd.DataFrame:
    """Return set *number*'s within-participant rows (binary, rating, numeric)."""
    rows = _within()
    return rows[rows["set"].eq(number)].reset_index(drop=True)


def ratings_tidy(number: int, column: str = "rating") -> pd.DataFrame:
    """Return set *number*'s ratings (or its numeric responses) as tidy rows of question q."""
    data = within(number)
    return rating_rows(data.assign(**{column: data[column].round(12)}), "q", column)


def pairwise_tidy(number: int) -> pd.DataFrame:
    """Return set *number*'s forced choices as tidy pairwise rows."""
    rows = _pairs()
    return pairwise_rows(rows[rows["set"].eq(number)])


def binary_problem(number: int) -> MixedProblem:
    """Return set *number*'s binary GLMM: binary ~ condition + (1 | participant) + (1 | item)."""
    data = within(number)
    return MixedProblem(
        y=data["binary"].to_numpy(float),
        X=np.column_stack([np.ones(len(data)), data["condition"].eq("on").to_numpy(float)]),
        fixed_names=("(Intercept)", "conditionon"),
        components=tuple(intercepts(data)),
    )
