"""Turn the reference data sets (tests/analysis/reference/mixed_*.csv) into tidy tables."""

from pathlib import Path

import pandas as pd

from analysis import check_responses

REFERENCE = Path(__file__).parent / "reference"


def _tidy(rows: pd.DataFrame) -> pd.DataFrame:
    base = {"study": "reference", "block": "main", "question": "", "rating": "", "text": ""}
    base.update({"rt_ms": "", "flags": "", "condition_b": "", "chosen": ""})
    for column, value in base.items():
        if column not in rows:
            rows[column] = value
    return check_responses(rows.astype(str))


def pairwise_rows(data: pd.DataFrame) -> pd.DataFrame:
    """Return rows with participant, item, clip1, clip2 and first (0/1) as tidy pairwise rows."""
    return _tidy(
        pd.DataFrame(
            {
                "participant": data["participant"],
                "trial": [f"t{i}" for i in range(len(data))],
                "item": data["item"],
                "kind": "pairwise",
                "condition_a": data["clip1"],
                "condition_b": data["clip2"],
                "chosen": data["clip1"].where(data["first"].eq(1), data["clip2"]),
            }
        )
    )


def rating_rows(data: pd.DataFrame, question: str, column: str = "rating") -> pd.DataFrame:
    """Return rows with participant, item, condition and *column* as tidy rating rows."""
    return _tidy(
        pd.DataFrame(
            {
                "participant": data["participant"],
                "trial": [f"t{i}" for i in range(len(data))],
                "item": data["item"],
                "kind": "rating",
                "condition_a": data["condition"],
                "question": question,
                "rating": data[column],
            }
        )
    )


def pairwise_tidy() -> pd.DataFrame:
    """Return the forced-choice reference data as tidy pairwise rows."""
    return pairwise_rows(pd.read_csv(REFERENCE / "mixed_pairwise.csv"))


def ratings_tidy(name: str = "mixed_ratings.csv", question: str = "clarity") -> pd.DataFrame:
    """Return a Likert reference data set as tidy rating rows of one question."""
    return rating_rows(pd.read_csv(REFERENCE / name), question)
