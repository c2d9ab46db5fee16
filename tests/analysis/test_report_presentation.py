"""The report as a reviewer reads it (issue 56, item 7): headed by the study's title,
tables headed in words, one legend entry per condition, medians visible on every box."""

import json

import pandas as pd
from matplotlib.colors import to_rgba

from analysis import ReportOptions, build_report, write_report
from analysis.figures import ratings_plot
from tests.analysis.mixed_data import pairwise_tidy, ratings_tidy


def test_the_report_is_headed_by_the_studys_title_and_its_tables_in_words(tmp_path):
    frame = pairwise_tidy()
    report = build_report(frame, ReportOptions(mixed_models=False), title="Spine motion")
    write_report(report, frame, tmp_path, draw_figures=False)
    html = (tmp_path / "report.html").read_text()
    assert "<h1>Spine motion: results</h1>" in html
    assert "<title>Spine motion — results</title>" in html
    assert json.loads((tmp_path / "results.json").read_text())["title"] == "Spine motion"
    for raw in ("a_wins", "p_one_sided_majority", "mean_participant_rate", "rank_biserial"):
        assert f"<th>{raw}</th>" not in html
    assert "<th>p (one-sided, majority)</th>" in html and "<th>a chosen</th>" in html
    # The CSV tables keep their column names for scripts.
    assert "p_one_sided_majority" in pd.read_csv(tmp_path / "pairs.csv").columns


def test_without_a_title_the_report_is_named_by_its_studies(tmp_path):
    frame = pairwise_tidy()
    report = build_report(frame, ReportOptions(mixed_models=False))
    write_report(report, frame, tmp_path, draw_figures=False)
    assert "<h1>Results" in (tmp_path / "report.html").read_text()


def test_the_ratings_legend_names_each_condition_once_and_medians_are_black():
    frame = pd.concat([ratings_tidy(), ratings_tidy(question="naturalness")])
    figure = ratings_plot(frame)
    labels = [text.get_text() for legend in figure.legends for text in legend.get_texts()]
    conditions = sorted(set(frame["condition_a"]) - {""})
    assert sorted(labels) == conditions
    medians = [
        line
        for axis in figure.axes
        for line in axis.get_lines()
        if len(line.get_xdata()) == 2 and line.get_linewidth() == 1.5
    ]
    assert medians and all(to_rgba(line.get_color()) == to_rgba("black") for line in medians)


def test_the_participant_flow_accounts_for_everyone_in_the_table(tmp_path):
    """Issue 56, item 6: from a response table alone, who answered anything started and
    consented; who is flagged incomplete did not finish; each exclusion is counted."""
    frame = pairwise_tidy()
    people = sorted(frame["participant"].unique())
    frame.loc[frame["participant"] == people[0], "flags"] = "incomplete"
    frame.loc[frame["participant"] == people[1], "flags"] = "pilot"
    report = build_report(frame, ReportOptions(mixed_models=False))
    flow = report.flow
    assert (flow.started, flow.consented, flow.finished) == (48, 48, 47)
    assert flow.excluded == {"pilot": 1, "incomplete": 1} and flow.analysed == 46
    assert flow.source == "response table"
    assert flow.apa() == (
        "Of 48 participants who started, 48 consented and 47 finished; 2 were excluded "
        "(1 pilot, 1 incomplete); 46 were analysed"
    )
    written = write_report(report, frame, tmp_path)
    assert "participant_flow.png" in written
    html = (tmp_path / "report.html").read_text()
    assert 'class="flow"' in html and "answered nothing are not in it" in html


def test_a_participant_with_only_one_condition_is_named_where_a_comparison_leaves_them_out():
    """Issue 56, item 6: who rated only one of two conditions is dropped from their paired
    tests; the comparison names them in its APA line and in results.json."""
    frame = ratings_tidy()
    conditions = sorted(set(frame["condition_a"]) - {""})
    who = sorted(frame["participant"].unique())[0]
    frame = frame[~((frame["participant"] == who) & (frame["condition_a"] == conditions[0]))]
    report = build_report(frame, ReportOptions(mixed_models=False))
    comparison = next(c for c in report.rating_condition_comparisons if conditions[0] in (c.a, c.b))
    assert comparison.left_out == (str(who),)
    assert f"with only one of the two conditions left out: {who}" in comparison.apa()


def test_wide_tables_scroll_inside_the_report_on_a_phone_and_a_laptop(browser, tmp_path):
    """The intelligibility comparisons table (19 columns) widened the whole page to
    1,756 px on a 1,366 px laptop; it now scrolls on its own."""
    from analysis import read_responses
    from tests.analysis.mixed_data import REFERENCE

    frame = read_responses(REFERENCE / "study_r.csv")
    report = build_report(frame, ReportOptions(mixed_models=False))
    write_report(report, frame, tmp_path, draw_figures=False)
    for width in (390, 1366):
        page = browser.new_page(viewport={"width": width, "height": 900})
        page.goto((tmp_path / "report.html").as_uri())
        widest = page.evaluate(
            "Math.max(...[...document.querySelectorAll('table')].map(t => t.scrollWidth))"
        )
        assert widest > width / 2  # the tables are there, and wide
        assert page.evaluate("document.documentElement.scrollWidth") == width
        page.close()
