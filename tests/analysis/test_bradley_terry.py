"""Fixed Bradley–Terry strengths: a closed form, and data with no finite estimate.

References: with two conditions the model is a single binomial, so the log-worth is the
log odds of the counts and its SE √(1/n₁ + 1/n₂) (Agresti, *Categorical Data Analysis*,
3rd ed., §11.6). For a disconnected comparison graph R's ``glm(cbind(w, l) ~ 0 + X,
binomial)`` reports the aliased condition as NA (issue 56: c4 = NA where we printed
±0.193); for separated data (a condition that never wins) no finite maximum-likelihood
estimate exists (Ford 1957), where we printed −20.57 with a CI of ±34,700.
"""

import dataclasses
import math

import pandas as pd
import pytest

from analysis.bradley_terry import bradley_terry, not_estimable
from analysis.mixed import mixed_bradley_terry
from tests.analysis import crossed_data


def _counts(rows) -> pd.DataFrame:
    return pd.DataFrame(rows, columns=["a", "b", "a_wins", "b_wins"])


def test_two_conditions_give_the_log_odds_and_its_standard_error():
    result = bradley_terry(_counts([("a", "b", 30, 10)]), ["a", "b"])
    b = result.strengths[1]
    assert result.not_estimable == "" and result.nobs == 40
    assert b.log_worth == pytest.approx(math.log(10 / 30))
    assert b.se == pytest.approx(math.sqrt(1 / 30 + 1 / 10))


def test_a_disconnected_design_is_not_estimable_and_says_which_groups():
    counts = _counts([("c1", "c2", 30, 18), ("c3", "c4", 20, 28)])
    result = bradley_terry(counts, ["c1", "c2", "c3", "c4"])
    assert result.strengths == () and math.isnan(result.log_likelihood)
    assert "separate groups: c1, c2; c3, c4" in result.not_estimable
    assert result.nobs == 96


def test_a_condition_that_never_wins_is_separation_not_a_number():
    pairs = [("c1", "c2", 12, 8), ("c1", "c3", 11, 9), ("c2", "c3", 9, 11)]
    pairs += [(c, "c4", 20, 0) for c in ("c1", "c2", "c3")]
    result = bradley_terry(_counts(pairs), ["c1", "c2", "c3", "c4"])
    assert result.strengths == ()
    assert result.not_estimable.startswith("c4 never beat any other condition")
    # One win for c4 makes every strength finite again.
    pairs[-1] = ("c3", "c4", 19, 1)
    fitted = bradley_terry(_counts(pairs), ["c1", "c2", "c3", "c4"])
    assert fitted.not_estimable == "" and all(math.isfinite(s.se) for s in fitted.strengths)
    assert not_estimable(_counts(pairs), ["c1", "c2", "c3", "c4"]) == ""


def test_a_mixed_fit_that_did_not_converge_prints_no_wald_test():
    result = mixed_bradley_terry(crossed_data.pairwise_tidy(1), ["a", "b", "c"])
    assert result.apa().startswith("Wald χ²(2)")
    stopped = dataclasses.replace(result, converged=False)
    assert stopped.apa().startswith("not tested: the fit did not converge")
    assert "χ²" not in stopped.apa()


def test_the_report_prints_not_estimable_with_the_reason(tmp_path):
    from analysis.outputs import write_report
    from analysis.report import ReportOptions, build_report
    from analysis.tidy import check_responses

    frame = crossed_data.pairwise_tidy(1)
    shows_c = frame["condition_a"].eq("c") | frame["condition_b"].eq("c")
    other = frame["condition_a"].where(frame["condition_b"].eq("c"), frame["condition_b"])
    frame.loc[shows_c, "chosen"] = other[shows_c]  # c never wins
    frame = check_responses(frame)
    report = build_report(frame, ReportOptions(conditions=("a", "b", "c"), mixed_models=False))
    assert report.pairwise.bradley_terry.not_estimable.startswith("c never beat")
    write_report(report, frame, tmp_path, draw_figures=False)
    html = (tmp_path / "report.html").read_text()
    assert "<strong>Not estimable:</strong> c never beat any other condition" in html
