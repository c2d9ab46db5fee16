"""Test the command line end to end, and that bad CSVs give one clear error line."""

import json
import re
import subprocess
import sys
from pathlib import Path

import pytest

from tests.analysis.published import table_3_rows, table_5_2_rows

ROOT = Path(__file__).resolve().parents[2]


def run(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run(
        [sys.executable, "-m", "analysis", *args], cwd=ROOT, capture_output=True, text=True
    )


def test_report_writes_every_output(tmp_path):
    csv = tmp_path / "responses.csv"
    table_5_2_rows().to_csv(csv, index=False)
    result = run("report", str(csv), "--out", str(tmp_path / "out"))
    assert result.returncode == 0, result.stderr
    out = tmp_path / "out"
    for name in (
        "results.json",
        "report.html",
        "pairs.csv",
        "pairs.tex",
        "pairs.md",
        "conditions.csv",
        "posthoc.csv",
        "items.csv",
        "condition_rates.png",
        "condition_rates.pdf",
        "pairwise_matrix.png",
        "pairwise_matrix.pdf",
    ):
        assert (out / name).exists(), name
    data = json.loads((out / "results.json").read_text())
    pair = data["pairwise"]["pairs"][0]
    # results.json speaks the result objects' vocabulary (issue 39), the tables a reader's.
    assert {
        "a",
        "b",
        "a_wins",
        "b_wins",
        "ties",
        "statistic",
        "pvalue",
        "pvalue_one_sided_majority",
        "nobs",
        "apa",
    } <= set(pair)
    assert {"condition", "shown", "chosen", "win_rate", "share", "sem"} <= set(
        data["pairwise"]["conditions"][0]
    )
    assert {"statistic", "df_num", "df_den", "pvalue", "pvalue_gg", "eta_p2", "nobs", "apa"} <= set(
        data["pairwise"]["rm_anova"]
    )
    posthoc = data["pairwise"]["posthoc"][0]
    assert {"a", "b", "statistic", "df", "pvalue", "pvalue_adjusted", "dz", "ci", "apa"} <= set(
        posthoc
    )
    assert "p_holm" not in posthoc  # the correction is named once, in pairwise.correction
    assert len(data["pairwise"]["items"]) == 48
    assert "\\toprule" in (out / "pairs.tex").read_text()
    html = (out / "report.html").read_text()
    assert "Repeated-measures ANOVA" in html and 'src="condition_rates.png"' in html


def test_condition_order_and_split_ties(tmp_path):
    csv = tmp_path / "responses.csv"
    table_3_rows().to_csv(csv, index=False)
    result = run(
        "report",
        str(csv),
        "--out",
        str(tmp_path / "o"),
        "--conditions",
        "spine,control",
        "--ties",
        "split",
        "--correction",
        "bonferroni",
        "--no-figures",
    )
    assert result.returncode == 0, result.stderr
    data = json.loads((tmp_path / "o" / "results.json").read_text())
    assert (data["pairwise"]["pairs"][0]["a"], data["pairwise"]["tie_handling"]) == (
        "spine",
        "split",
    )
    assert data["pairwise"]["correction"] == "bonferroni"
    assert not (tmp_path / "o" / "condition_rates.png").exists()


def _broken(tmp_path, change) -> Path:
    frame = table_3_rows()
    frame = change(frame)
    path = tmp_path / "broken.csv"
    frame.to_csv(path, index=False)
    return path


@pytest.mark.parametrize(
    "change, message",
    [
        (
            lambda f: f.drop(columns=["chosen", "rt_ms"]),
            "broken.csv: missing column(s) chosen, rt_ms",
        ),
        (
            lambda f: f.assign(chosen=["telepathy", *list(f["chosen"][1:])]),
            "broken.csv: row 1 (line 2): chosen 'telepathy' is neither condition_a",
        ),
        (
            lambda f: f.assign(
                kind=["rating"] * len(f), question="clarity", rating=["good"] + ["3"] * (len(f) - 1)
            ),
            "broken.csv: row 1 (line 2): rating 'good' is not a number.",
        ),
        (
            lambda f: f.assign(kind=["vote", *list(f["kind"][1:])]),
            "broken.csv: row 1 (line 2): kind 'vote' is not one of pairwise, comparative",
        ),
        (
            lambda f: f.assign(flags=["maybe"] + [""] * (len(f) - 1)),
            "broken.csv: row 1 (line 2): unknown flag 'maybe'",
        ),
        (
            lambda f: f.assign(rt_ms=["fast"] + [""] * (len(f) - 1)),
            "broken.csv: row 1 (line 2): rt_ms 'fast' is not a number.",
        ),
        (lambda f: f.iloc[0:0], "broken.csv: no response rows."),
    ],
)
def test_malformed_csv_gives_one_clear_line(tmp_path, change, message):
    result = run("report", str(_broken(tmp_path, change)), "--out", str(tmp_path / "o"))
    assert result.returncode == 2
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1, result.stderr
    assert lines[0].startswith("error: ") and message in lines[0]
    assert not (tmp_path / "o").exists()


@pytest.mark.parametrize(
    "conditions, message",
    [
        ("control,spine,extra", "condition(s) extra never shown"),
        ("control", "unknown condition(s) spine; expected control"),
    ],
)
def test_condition_list_mismatch_is_named(tmp_path, conditions, message):
    csv = tmp_path / "r.csv"
    table_3_rows().to_csv(csv, index=False)
    result = run("report", str(csv), "--out", str(tmp_path / "o"), "--conditions", conditions)
    assert result.returncode == 2
    assert message in result.stderr and len(result.stderr.strip().splitlines()) == 1


def test_missing_and_non_csv_files(tmp_path):
    assert run("report", str(tmp_path / "nope.csv"), "--out", str(tmp_path)).stderr == (
        f"error: {tmp_path / 'nope.csv'}: no such file.\n"
    )
    binary = tmp_path / "b.csv"
    binary.write_bytes(b"\x89PNG\r\n\x1a\n\x00\x00")
    result = run("report", str(binary), "--out", str(tmp_path / "o"))
    assert result.returncode == 2 and len(result.stderr.strip().splitlines()) == 1


def test_markdown_tables_keep_a_hostile_label_as_text(tmp_path):
    """Issue 51: condition labels went unescaped into the report's Markdown tables, so a
    label could split a column or carry HTML into whatever renders the file."""
    csv = tmp_path / "responses.csv"
    rows = table_5_2_rows()
    hostile = "Var | <img src=x onerror=alert(1)> [x](javascript:y)"
    first = rows["condition_a"].iloc[0]
    for column in ("condition_a", "condition_b", "chosen"):
        rows[column] = rows[column].replace(first, hostile)
    rows.to_csv(csv, index=False)
    result = run("report", str(csv), "--out", str(tmp_path / "out"))
    assert result.returncode == 0, result.stderr
    for name in ("pairs.md", "conditions.md"):
        lines = (tmp_path / "out" / name).read_text().splitlines()
        header_columns = lines[0].count("|")
        assert all(line.count("|") - line.count("\\|") == header_columns for line in lines)
        text = "\n".join(lines)
        assert not re.search(r"(?<!\\)[<\]]", text) and "\\<img" in text
