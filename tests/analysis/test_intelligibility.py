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


def test_letters_of_any_script_are_kept_so_a_turkish_answer_is_not_misscored():
    """Issue 55: words('ÇAY') was ['AY'], so "AY" (moon) scored 1.0 for "ÇAY" (tea) and
    ÖĞRETMEN became RETMEN."""
    assert words("ÇAY") == ["ÇAY"] and words("Ç-A-Y içtim") == ["ÇAY", "IÇTIM"]
    assert words("öğretmen") == ["ÖĞRETMEN"]
    assert word_accuracy("ay", "ÇAY") == 0.0 and word_accuracy("çay", "ÇAY") == 1.0
    assert word_accuracy("İYİ", "iyi") == 1.0  # dotted and dotless capitals match
    assert words("não sei") == ["NÃO", "SEI"] and words("CAN'T find") == ["CAN'T", "FIND"]
    assert words("can’t") == ["CAN'T"]
    decomposed = "ça".replace("ç", "c\u0327")  # c + combining cedilla
    assert words(decomposed) == ["ÇA"]
