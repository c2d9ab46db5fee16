"""Golden test of the whole report on a small data set, against R.

Data: tests/analysis/reference/small_study.csv (make_small_study.py). Reference values:
small_study.json, computed from the CSV by base R 4.2 (small_study.R): binom.test,
t.test(paired = TRUE), p.adjust("holm"), quantile(type = 7), and the exact signed-rank
p by enumeration.
"""

import itertools
import json
import re
from pathlib import Path

import pandas as pd
import pytest

from analysis import ReportOptions, build_report, read_responses, results_json, write_report
from analysis.figures import condition_rates_plot, pairwise_matrix_plot, ratings_plot
from tests.analysis.published import table_5_2_rows

REFERENCE = Path(__file__).parent / "reference"
R = json.loads((REFERENCE / "small_study.json").read_text())
close = pytest.approx
TOLERANCE = 1e-9


@pytest.fixture(scope="module")
def written(tmp_path_factory):
    out = tmp_path_factory.mktemp("small")
    frame = read_responses(REFERENCE / "small_study.csv")
    report = build_report(frame, ReportOptions(mixed_models=False), source="small_study.csv")
    names = write_report(report, frame, out, draw_figures=False)
    return out, names, report


def _table(out: Path, name: str) -> list[dict]:
    return pd.read_csv(out / f"{name}.csv").to_dict("records")


def _pairs(rows: list[dict]) -> dict:
    return {(row["a"], row["b"]): row for row in rows}


def test_every_statistic_has_a_table(written):
    out, names, _ = written
    for name in (
        "pairs",
        "posthoc",
        "wilcoxon",
        "rating_conditions",
        "rating_comparisons",
        "rating_condition_comparisons",
        "intelligibility_conditions",
        "intelligibility_comparisons",
    ):
        assert {f"{name}.csv", f"{name}.md", f"{name}.tex"} <= set(names), name
    assert list(pd.read_csv(out / "posthoc.csv").columns) == [
        "a",
        "b",
        "t",
        "df",
        "p",
        "p_adjusted",
        "dz",
        "dz_ci_low",
        "dz_ci_high",
        "mean_difference",
        "ci_low",
        "ci_high",
        "apa",
    ]
    assert list(pd.read_csv(out / "wilcoxon.csv").columns) == [
        "a",
        "b",
        "V",
        "p",
        "p_adjusted",
        "method",
        "rank_biserial",
        "n",
        "apa",
    ]


def test_binomial_tests_match_r(written):
    ours = _pairs(_table(written[0], "pairs"))
    for expected in R["pairs"]:
        row = ours[(expected["a"], expected["b"])]
        assert (row["a_wins"], row["b_wins"], row["ties"]) == (
            expected["a_wins"],
            expected["b_wins"],
            expected["ties"],
        )
        assert row["p_two_sided"] == close(expected["p"], rel=TOLERANCE)
        assert row["p_adjusted"] == close(expected["p_adjusted"], rel=TOLERANCE)


def test_posthoc_t_tests_with_ci_and_apa_match_r(written):
    ours = _pairs(_table(written[0], "posthoc"))
    assert len(ours) == len(R["posthoc"]) == 3
    for expected in R["posthoc"]:
        row = ours[(expected["a"], expected["b"])]
        for column in ("t", "p", "p_adjusted", "dz", "mean_difference"):
            assert row[column] == close(expected[column], rel=TOLERANCE), column
        assert (row["ci_low"], row["ci_high"]) == close(expected["ci"], rel=TOLERANCE)
        assert (row["dz_ci_low"], row["dz_ci_high"]) == close(expected["dz_ci"], abs=1e-7)
        assert row["df"] == expected["df"]
        low, high = (f"{v:.2f}" for v in expected["ci"])
        assert f"(95 % CI {low} to {high}), t(5) = {expected['t']:.2f}" in row["apa"]


def test_wilcoxon_tests_match_r(written):
    ours = _pairs(_table(written[0], "wilcoxon"))
    for expected in R["wilcoxon"]:
        row = ours[(expected["a"], expected["b"])]
        assert row["V"] == expected["V"] and row["method"] == expected["method"]
        assert row["p"] == close(expected["p"], rel=TOLERANCE)
        assert row["p_adjusted"] == close(expected["p_adjusted"], rel=TOLERANCE)
        assert row["rank_biserial"] == close(expected["r"], rel=TOLERANCE)
        assert row["n"] == expected["n"]


@pytest.mark.parametrize("measure", ["ratings", "intelligibility"])
def test_condition_summaries_across_items_match_r(written, measure):
    name = "rating" if measure == "ratings" else "intelligibility"
    ours = {row["condition"]: row for row in _table(written[0], f"{name}_conditions")}
    for expected in R[measure]["conditions"]:
        row = ours[expected["condition"]]
        assert (row["answers"], row["participants"], row["items"]) == (expected["n"], 6, 3)
        for column in ("mean", "sd", "sem", "median", "q1", "q3"):
            assert row[column] == close(expected[column], rel=TOLERANCE, abs=1e-12), column
        assert (row["ci_low"], row["ci_high"]) == close(expected["ci"], rel=TOLERANCE)


@pytest.mark.parametrize("measure", ["ratings", "intelligibility"])
def test_condition_comparisons_across_items_match_r(written, measure):
    name = "rating_condition" if measure == "ratings" else "intelligibility"
    ours = _pairs(_table(written[0], f"{name}_comparisons"))
    for expected in R[measure]["comparisons"]:
        row = ours[(expected["a"], expected["b"])]
        for column, theirs in (
            ("t", "t"),
            ("t_p", "p"),
            ("t_p_adjusted", "t_p_adjusted"),
            ("dz", "dz"),
            ("mean_difference", "mean_difference"),
            ("wilcoxon_V", "wilcoxon_V"),
            ("wilcoxon_p", "wilcoxon_p"),
            ("wilcoxon_p_adjusted", "wilcoxon_p_adjusted"),
            ("rank_biserial", "rank_biserial"),
        ):
            assert row[column] == close(expected[theirs], rel=TOLERANCE), column
        assert (row["ci_low"], row["ci_high"]) == close(expected["ci"], rel=TOLERANCE)
        assert (row["dz_ci_low"], row["dz_ci_high"]) == close(expected["dz_ci"], abs=1e-7)


def test_report_names_conditions_by_label_and_keeps_the_keys(written):
    out = written[0]
    data = json.loads((out / "results.json").read_text())
    assert data["design"]["conditions"] == ["Bayesian timing", "Constant timing", "Motion capture"]
    assert data["design"]["condition_keys"] == {
        "Bayesian timing": "bayes",
        "Constant timing": "ctl",
        "Motion capture": "mocap",
    }
    assert data["design"]["items"] == ["GUITAR", "MY-HOUSE", "TOY-CAR"]
    assert data["design"]["practice_items"] == ["HELLO"]
    html = (out / "report.html").read_text()
    assert "Items: GUITAR, MY-HOUSE, TOY-CAR." in html
    assert "Practice (not analysed): HELLO." in html
    assert "Motion capture = <code>mocap</code>" in html


def test_report_html_prints_every_apa_line_and_no_placeholders(written):
    out, _, _ = written
    html = (out / "report.html").read_text()
    data = json.loads((out / "results.json").read_text())
    lines = [t["apa"] for t in data["pairwise"]["posthoc"] + data["pairwise"]["wilcoxon"]]
    for name in (
        "rating_comparisons",
        "rating_condition_comparisons",
        "intelligibility_comparisons",
    ):
        lines += [c["apa"] for c in data[name]]
    for line in lines:
        assert line.replace("<", "&lt;") in html, line
    assert "p &lt; .001" in html and "p < .001" not in html
    text = re.sub(r"<[^>]+>", " ", html)
    for placeholder in ("None", "nan", "-0.00", " to  "):
        assert placeholder not in text, placeholder


def test_one_participant_prints_no_test_and_no_empty_interval(tmp_path):
    frame = read_responses(REFERENCE / "small_study.csv")
    alone = frame[frame["participant"] == "P1"]
    comparative = alone[alone["kind"] == "pairwise"].assign(kind="comparative", rating=2.0)
    alone = pd.concat([alone, comparative], ignore_index=True)
    report = build_report(alone, ReportOptions(mixed_models=False))
    write_report(report, alone, tmp_path, draw_figures=False)
    data = results_json(report)
    for preference in data["comparative"]:
        assert "95 % CI not computed" in preference["apa"]
        assert "V not computed (n = 1" in preference["apa"]
        assert preference["statistic"] is None and preference["rank_biserial"] is None
    text = re.sub(r"<[^>]+>", " ", (tmp_path / "report.html").read_text())
    for placeholder in ("None", "nan", "V = 0,", "r = -1.00", "r = 1.00", " to  ", " to ."):
        assert placeholder not in text, placeholder
    for name in ("rating_conditions", "intelligibility_conditions"):
        table = (tmp_path / f"{name}.md").read_text()
        assert "None" not in table and "nan" not in table


def _overlaps(figure) -> list[tuple[str, str]]:
    """Return the pairs of visible texts in *figure* whose drawn boxes intersect."""
    from matplotlib.text import Text

    figure.canvas.draw()
    renderer = figure.canvas.get_renderer()
    boxes = [
        (t.get_text(), t.get_window_extent(renderer))
        for t in figure.findobj(Text)
        if t.get_visible() and t.get_text().strip()
    ]
    return [
        (a, b)
        for (a, box_a), (b, box_b) in itertools.combinations(boxes, 2)
        if box_a.overlaps(box_b)
    ]


LONG = {
    "Constant": "Constant timing",
    "Mocap": "Motion capture of a native signer",
    "Normalized": "Normalized timing",
    "Variable": "Variable timing",
}


def _check(frame: pd.DataFrame) -> pd.DataFrame:
    from analysis import check_responses

    return check_responses(frame.astype(str).replace("nan", ""))


def test_figure_labels_never_overlap():
    """Measure every text's drawn box: long labels, simulated ones longer still."""
    import matplotlib.pyplot as plt

    frame = table_5_2_rows()
    shows_mocap = frame["condition_a"].eq("Mocap") | frame["condition_b"].eq("Mocap")
    long = _check(
        frame.assign(
            condition_a_label=frame["condition_a"].map(LONG),
            condition_b_label=frame["condition_b"].map(LONG),
            condition_simulated=shows_mocap.map({True: "Mocap", False: ""}),
        )
    )
    small = read_responses(REFERENCE / "small_study.csv")
    for data in (small, long, _check(table_5_2_rows())):
        report = build_report(data, ReportOptions(mixed_models=False))
        figures = [condition_rates_plot(report), pairwise_matrix_plot(report)]
        if report.ratings:
            figures.append(ratings_plot(data))
        for figure in figures:
            assert _overlaps(figure) == []
            plt.close(figure)
    report = build_report(long, ReportOptions(mixed_models=False))
    assert "Motion capture of a native signer (simulated)" in [
        c.condition for c in report.pairwise.conditions
    ]
