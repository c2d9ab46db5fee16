"""Test that a simulated condition is labelled simulated in every output of a report."""

import json
import re

import matplotlib
import pandas as pd
import pytest

from analysis import ReportOptions, build_report, check_responses
from analysis.figures import condition_rates_figure, pairwise_matrix_figure, ratings_figure
from tests.analysis.published import COLUMNS, table_5_2_rows
from tests.analysis.test_cli import run

KEY = "Mocap"  # seed 000 Table 5.2's name for the motion-capture condition
LABEL = f"{KEY} (simulated)"


def with_simulated_mocap(frame: pd.DataFrame) -> pd.DataFrame:
    shows = frame["condition_a"].eq(KEY) | frame["condition_b"].eq(KEY)
    return frame.assign(condition_simulated=shows.map({True: KEY, False: ""}))


def rating_rows() -> pd.DataFrame:
    rows = []
    for condition, values in ((KEY, [4, 5, 4, 3]), ("Variable", [3, 3, 2, 4])):
        for participant, value in enumerate(values):
            row = dict.fromkeys(COLUMNS, "")
            row.update(
                participant=f"R{participant}",
                study="fingerspelling",
                block="ratings",
                trial=f"rate-{condition}",
                item="GUITAR",
                kind="rating",
                condition_a=condition,
                question="natural",
                rating=str(value),
                condition_simulated=KEY if condition == KEY else "",
            )
            rows.append(row)
    return pd.DataFrame(rows)


def test_checking_the_table_names_simulated_conditions_everywhere_they_appear():
    table = check_responses(with_simulated_mocap(table_5_2_rows()))
    shown = set(table["condition_a"]) | set(table["condition_b"]) | set(table["chosen"])
    assert LABEL in shown and KEY not in shown
    # Checking again (a report of a checked table) does not label twice.
    assert check_responses(table)["condition_a"].str.count("simulated").max() == 1


def test_a_condition_order_may_name_the_simulated_condition_by_its_key():
    table = check_responses(with_simulated_mocap(table_5_2_rows()))
    options = ReportOptions(
        conditions=(KEY, "Variable", "Constant", "Normalized"), mixed_models=False
    )
    report = build_report(table, options)
    assert next(c.condition for c in report.pairwise.conditions) == LABEL
    assert report.design["simulated_conditions"] == [LABEL]


def test_every_output_of_the_command_line_report_says_simulated(tmp_path):
    csv = tmp_path / "responses.csv"
    frame = pd.concat([with_simulated_mocap(table_5_2_rows()), rating_rows()])
    frame.fillna("").to_csv(csv, index=False)
    result = run("report", str(csv), "--out", str(tmp_path / "out"))
    assert result.returncode == 0, result.stderr
    out = tmp_path / "out"
    naming = []
    for path in sorted(out.iterdir()):
        if path.suffix in (".json", ".html", ".csv", ".tex", ".md"):
            text = path.read_text()
            if KEY in text:
                naming.append(path.name)
                # every mention carries the label (LaTeX escapes nothing in it)
                assert text.count(KEY) == text.count(LABEL), path.name
    for name in (
        "results.json",
        "report.html",
        "pairs.csv",
        "pairs.tex",
        "pairs.md",
        "conditions.csv",
        "conditions.tex",
        "items.tex",
        "ratings.tex",
    ):
        assert name in naming
    html = (out / "report.html").read_text()
    assert 'class="simulated"' in html and "not recorded human motion" in html
    data = json.loads((out / "results.json").read_text())
    assert data["design"]["simulated_conditions"] == [LABEL]


@pytest.mark.parametrize("draw", [condition_rates_figure, pairwise_matrix_figure, ratings_figure])
def test_figures_label_the_simulated_condition(tmp_path, draw):
    frame = pd.concat([with_simulated_mocap(table_5_2_rows()), rating_rows()]).fillna("")
    table = check_responses(frame)
    report = build_report(table, ReportOptions(mixed_models=False))
    # Text as text, not glyph outlines, so the SVG can be searched.
    with matplotlib.rc_context({"svg.fonttype": "none"}):
        if draw is ratings_figure:
            (name,) = draw(report, table, tmp_path, formats=("svg",))
        else:
            (name,) = draw(report, tmp_path, formats=("svg",))
    svg = (tmp_path / name).read_text()
    # A long tick label is wrapped onto lines, one <text> each: read the words in order.
    words = " ".join(re.findall(r"<text[^>]*>([^<]*)</text>", svg))
    assert LABEL in " ".join(words.split())
