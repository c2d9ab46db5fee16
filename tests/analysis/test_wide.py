"""Test the column-mapping import of wide survey exports into the tidy format."""

import io
import json
import subprocess
import sys
from pathlib import Path

import pandas as pd
import pytest

from analysis import TidyFormatError, analyze_pairwise, parse_mapping, wide_to_tidy

ROOT = Path(__file__).resolve().parents[2]

# SurveyMonkey style: question text in the first header row, answer option in the second.
SURVEYMONKEY = (
    "Respondent ID,What is your age?,Page 3: Which animation is most natural?,"
    "Page 4: Which animation is most natural?,Rate the clarity,What did you understand?\n"
    ",Response,Response,Response,Response,Open-Ended Response\n"
    """1001,26-35,Clip 1,Clip 2,Very clear,guitar
1002,18-25,Clip 2,Cannot see a difference,3,gitar
1003,26-35,Clip 1,,Very confusing,
"""
)

MAPPING = {
    "format": "signstudy.wide-mapping",
    "study": "fingerspelling",
    "header_rows": 2,
    "participant": "Respondent ID",
    "attributes": {"age": "What is your age?"},
    "columns": [
        {
            "column": "Page 3: Which animation is most natural?",
            "kind": "pairwise",
            "trial": "cmp-01",
            "item": "GUITAR",
            "condition_a": "constant",
            "condition_b": "mocap",
            "answers": {"Clip 1": "a", "Clip 2": "b", "Cannot see a difference": "none"},
        },
        {
            "column": "Page 4: Which animation is most natural? | Response",
            "kind": "pairwise",
            "trial": "cmp-02",
            "item": "GUITAR",
            "condition_a": "mocap",
            "condition_b": "constant",
            "answers": {"Clip 1": "a", "Clip 2": "b", "Cannot see a difference": "none"},
        },
        {
            "column": "Rate the clarity",
            "kind": "rating",
            "trial": "rate-1",
            "item": "GUITAR",
            "condition_a": "variable",
            "question": "clarity",
            "answers": {"Very confusing": 1, "Very clear": 5},
        },
        {
            "column": "What did you understand?",
            "kind": "text",
            "trial": "intel-1",
            "item": "GUITAR",
            "condition_a": "variable",
            "question": "intelligibility",
            "target": "GUITAR",
        },
    ],
}


def _wide(text: str, header_rows: int) -> pd.DataFrame:
    header = [0, 1] if header_rows == 2 else 0
    return pd.read_csv(io.StringIO(text), dtype=str, keep_default_na=False, header=header)


def test_surveymonkey_export_becomes_tidy_rows():
    tidy = wide_to_tidy(_wide(SURVEYMONKEY, 2), parse_mapping(MAPPING))
    assert len(tidy) == 3 * 4 - 2  # two unanswered cells give no row
    first = tidy[(tidy["participant"] == "1001") & (tidy["trial"] == "cmp-01")].iloc[0]
    assert (first["chosen"], first["age"], first["study"]) == (
        "constant",
        "26-35",
        "fingerspelling",
    )
    swapped = tidy[(tidy["participant"] == "1001") & (tidy["trial"] == "cmp-02")].iloc[0]
    assert swapped["chosen"] == "constant"  # Clip 2 of a (mocap, constant) page
    tie = tidy[(tidy["participant"] == "1002") & (tidy["trial"] == "cmp-02")].iloc[0]
    assert tie["chosen"] == "none"
    ratings = tidy[tidy["kind"] == "rating"].set_index("participant")["rating"]
    assert ratings.to_dict() == {"1001": 5.0, "1002": 3.0, "1003": 1.0}
    result = analyze_pairwise(tidy)
    # constant: 1001 twice, 1003 once; mocap: 1002 once; one tie.
    assert (result.pairs[0].a_wins, result.pairs[0].b_wins, result.ties) == (3, 1, 1)


def test_unknown_answer_label_is_named():
    text = SURVEYMONKEY.replace("1003,26-35,Clip 1", "1003,26-35,Clip 3")
    with pytest.raises(TidyFormatError, match=r"row 3, column 'Page 3: .*': answer 'Clip 3'"):
        wide_to_tidy(_wide(text, 2), parse_mapping(MAPPING))


def test_missing_column_is_named():
    mapping = {**MAPPING, "participant": "ResponseId"}
    with pytest.raises(TidyFormatError, match="no column 'ResponseId' in the survey export"):
        wide_to_tidy(_wide(SURVEYMONKEY, 2), parse_mapping(mapping))


@pytest.mark.parametrize(
    "change, message",
    [
        ({"format": "x"}, "not a column mapping"),
        ({"columns": [{"column": "Q1", "kind": "vote", "trial": "t"}]}, "kind 'vote'"),
        ({"columns": [{"column": "Q1", "kind": "rating"}]}, "needs 'trial'"),
        (
            {"columns": [{"column": "Q1", "kind": "rating", "trial": "t", "colour": 1}]},
            "unknown key",
        ),
    ],
)
def test_bad_mappings_are_rejected(change, message):
    with pytest.raises(TidyFormatError, match=message):
        parse_mapping({**MAPPING, **change})


def test_command_line_import_then_report(tmp_path):
    qualtrics = "ResponseId,Q1,Q2\nR_1,Clip 1,Clip 2\nR_2,Clip 2,Clip 2\n"
    (tmp_path / "survey.csv").write_text(qualtrics)
    mapping = {
        "format": "signstudy.wide-mapping",
        "study": "s",
        "participant": "ResponseId",
        "columns": [
            {
                "column": q,
                "kind": "pairwise",
                "trial": q,
                "item": "W",
                "condition_a": "x",
                "condition_b": "y",
                "answers": {"Clip 1": "a", "Clip 2": "b"},
            }
            for q in ("Q1", "Q2")
        ],
    }
    (tmp_path / "map.json").write_text(json.dumps(mapping))
    run = [sys.executable, "-m", "analysis"]
    imported = subprocess.run(
        [
            *run,
            "import-wide",
            str(tmp_path / "survey.csv"),
            "--mapping",
            str(tmp_path / "map.json"),
            "--out",
            str(tmp_path / "tidy.csv"),
        ],
        cwd=ROOT,
        capture_output=True,
        text=True,
    )
    assert imported.returncode == 0, imported.stderr
    assert "Wrote 4 tidy rows for 2 participants" in imported.stdout
    report = subprocess.run(
        [*run, "report", str(tmp_path / "tidy.csv"), "--out", str(tmp_path / "r"), "--no-figures"],
        cwd=ROOT,
        capture_output=True,
        text=True,
    )
    assert report.returncode == 0, report.stderr
    pairs = json.loads((tmp_path / "r" / "results.json").read_text())["pairwise"]["pairs"]
    assert (pairs[0]["a_wins"], pairs[0]["b_wins"]) == (1, 3)
