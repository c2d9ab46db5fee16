"""Test word-level scoring of typed answers."""

import pandas as pd
import pytest

from analysis import check_responses, score_intelligibility, word_accuracy, words
from tests.analysis.published import COLUMNS


def test_fingerspelled_glosses_become_words():
    assert words("HAVE LITTLE T-O-Y C-A-R.") == ["HAVE", "LITTLE", "TOY", "CAR"]
    assert words("looking-back") == ["LOOKING", "BACK"]


@pytest.mark.parametrize(
    "answer, target, fuzzy, expected",
    [
        ("elephant", "ELEPHANT", True, 1.0),
        ("elefant", "ELEPHANT", True, 1.0),
        ("elefant", "ELEPHANT", False, 0.0),
        ("a little toy", "HAVE LITTLE T-O-Y C-A-R", True, 0.5),
        ("car car car", "CAR", True, 1.0),
        ("car", "CAR CAR", True, 0.5),  # each answer word counts once
        ("", "GUITAR", True, 0.0),
    ],
)
def test_word_accuracy(answer, target, fuzzy, expected):
    assert word_accuracy(answer, target, fuzzy) == expected


def test_scores_average_per_condition_and_item():
    rows = []
    for participant, (condition, answer) in enumerate(
        [("variable", "guitar"), ("variable", "gutar"), ("constant", "quitter"), ("constant", "")]
    ):
        row = dict.fromkeys(COLUMNS, "")
        row.update(
            participant=f"P{participant}",
            study="s",
            trial="t",
            item="GUITAR",
            kind="text",
            condition_a=condition,
            question="intelligibility",
            text=answer,
            target="GUITAR",
        )
        rows.append(row)
    scores = score_intelligibility(check_responses(pd.DataFrame(rows)))
    by_condition = {s.condition: s for s in scores}
    assert by_condition["variable"].mean_accuracy == 1.0
    assert by_condition["constant"].mean_accuracy == 0.0
    assert by_condition["variable"].n == 2


def test_no_target_column_means_no_scoring():
    row = dict.fromkeys(COLUMNS, "")
    row.update(participant="P1", kind="text", text="comments")
    assert score_intelligibility(check_responses(pd.DataFrame([row]))) == ()
