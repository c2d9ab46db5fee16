"""Golden tests of the mixed models' formulas, results and report section."""

import json

import numpy as np
import pandas as pd
import pytest
from scipy.special import expit

from analysis import ReportOptions, build_report, results_json
from analysis.mixed import (
    Bernoulli,
    CumulativeLogit,
    Davidson,
    fit_mixed_models,
    mixed_bradley_terry,
    ordinal_mixed,
)
from analysis.mixed.families import FIRST, SECOND, TIE
from analysis.outputs import write_report
from analysis.tidy import TidyFormatError
from tests.analysis.mixed_data import pairwise_tidy, ratings_tidy

ETA = np.linspace(-6, 6, 25)


def _numeric(family, y, extra, step=1e-5):
    up = family.derivatives(ETA + step, y, extra).loglik
    down = family.derivatives(ETA - step, y, extra).loglik
    mid = family.derivatives(ETA, y, extra).loglik
    return (up - down) / (2 * step), -(up - 2 * mid + down) / step**2


@pytest.mark.parametrize(
    ("family", "y", "extra"),
    [
        (Bernoulli(), np.ones_like(ETA), np.zeros(0)),
        (Bernoulli(), np.zeros_like(ETA), np.zeros(0)),
        (Davidson(), np.full_like(ETA, FIRST), np.array([-0.3])),
        (Davidson(), np.full_like(ETA, SECOND), np.array([0.4])),
        (Davidson(), np.full_like(ETA, TIE), np.array([0.4])),
        (CumulativeLogit(4), np.zeros_like(ETA), np.array([-1.0, 0.2, 1.5])),
        (CumulativeLogit(4), np.full_like(ETA, 2.0), np.array([-1.0, 0.2, 1.5])),
        (CumulativeLogit(4), np.full_like(ETA, 3.0), np.array([-1.0, 0.2, 1.5])),
    ],
)
def test_family_derivatives_match_finite_differences(family, y, extra):
    derivs = family.derivatives(ETA, y, extra)
    gradient, weight = _numeric(family, y, extra)
    assert derivs.gradient == pytest.approx(gradient, abs=1e-6)
    assert derivs.weight == pytest.approx(weight, abs=2e-4)
    assert np.all(derivs.weight > 0)  # log-concave: the conditional mode is unique


def test_davidson_without_ties_is_the_logistic_model():
    """With ν → 0 a Davidson win has the Bradley–Terry probability logit⁻¹(η)."""
    won = Davidson().derivatives(ETA, np.full_like(ETA, FIRST), np.array([-40.0]))
    assert np.exp(won.loglik) == pytest.approx(expit(ETA), rel=1e-9)


def test_davidson_probabilities_sum_to_one():
    total = sum(
        np.exp(Davidson().derivatives(ETA, np.full_like(ETA, code), np.array([0.2])).loglik)
        for code in (FIRST, SECOND, TIE)
    )
    assert total == pytest.approx(1.0)


def test_cumulative_logit_probabilities_sum_to_one_far_in_the_tails():
    thresholds = np.array([-1.0, 0.2, 1.5])
    eta = np.array([-40.0, -5.0, 0.0, 5.0, 40.0])
    total = sum(
        np.exp(CumulativeLogit(4).derivatives(eta, np.full_like(eta, k), thresholds).loglik)
        for k in range(4)
    )
    assert total == pytest.approx(1.0)


def test_threshold_parametrisation_round_trips():
    family = CumulativeLogit(5)
    natural = np.array([-2.0, -0.5, 0.1, 3.0])
    assert family.extra_natural(family.extra_free(natural)) == pytest.approx(natural)


def _tied(frame: pd.DataFrame, rng: np.random.Generator, nu: float) -> pd.DataFrame:
    """Turn some decisive answers into ties, with the Davidson share ν/(2+ν) at η = 0."""
    frame = frame.copy()
    tie = rng.random(len(frame)) < nu / (2 + nu)
    frame.loc[tie, "chosen"] = "none"
    return frame


def test_davidson_model_recovers_strengths_with_ties():
    rng = np.random.default_rng(7)
    frame = _tied(pairwise_tidy(), rng, nu=0.8)
    excluded = mixed_bradley_terry(frame, ["a", "b", "c", "d"], random_strengths=False)
    davidson = mixed_bradley_terry(
        frame, ["a", "b", "c", "d"], ties="davidson", random_strengths=False
    )
    assert davidson.tie_handling == "davidson" and davidson.tie_parameter > 0
    assert davidson.nobs > excluded.nobs
    # Generated strengths (make_mixed_reference.py): b 0.8, c 0.4, d 1.1. The Davidson
    # log-worths are on half the logistic scale's spread at equal ν, so compare ranks
    # and signs, and that each CI is far from zero.
    assert [e.name for e in sorted(davidson.effects, key=lambda e: e.estimate)] == ["c", "b", "d"]
    assert all(e.ci[0] > 0 for e in davidson.effects)
    assert any("modelled as ties" in note for note in davidson.notes)


def test_result_objects_render():
    result = mixed_bradley_terry(pairwise_tidy(), ["a", "b", "c", "d"], random_strengths=False)
    data = result.to_dict()
    json.dumps(data)
    assert result.apa().startswith("Wald χ²(3) = ")
    assert result.df == 3 and result.pvalue < 0.001 and result.nobs == 2304
    assert "participant" in result.summary() and "position (clip 1)" in result.summary()
    assert len(result.contrasts) == 6
    d_vs_a = next(c for c in result.contrasts if (c.a, c.b) == ("d", "a"))
    assert d_vs_a.estimate == pytest.approx(result.effects[2].estimate)
    assert d_vs_a.apa().startswith("d − a = ")


def test_random_strengths_are_added_where_identifiable():
    frame = pairwise_tidy()
    frame = frame[frame["participant"] <= "P24"]
    result = mixed_bradley_terry(frame, ["a", "b", "c", "d"], random_strengths=None)
    assert [c.name for c in result.random] == [
        "participant",
        "item",
        "participant × condition strengths",
    ]
    # The data were generated with participants' own strength of b (SD 0.6).
    assert result.random[2].sd > 0.1


def test_ordinal_result_has_thresholds_and_the_assumption_check():
    result = ordinal_mixed(ratings_tidy(), "clarity")
    assert [t.name for t in result.thresholds] == ["1|2", "2|3", "3|4", "4|5"]
    assert result.proportional_odds.holds
    assert "proportional odds holds" in result.summary()


def test_too_little_data_is_refused_by_name():
    frame = pairwise_tidy()
    with pytest.raises(TidyFormatError, match="decisive judgements"):
        mixed_bradley_terry(frame.head(5), ["a", "b", "c", "d"])
    with pytest.raises(TidyFormatError, match="not in the condition order"):
        mixed_bradley_terry(frame, ["a", "b"])
    with pytest.raises(TidyFormatError, match="two or more conditions"):
        ordinal_mixed(ratings_tidy().query("condition_a == 'a'"), "clarity")


def test_small_studies_are_skipped_with_a_reason():
    frame = pairwise_tidy()
    few = frame[frame["participant"].isin(["P01", "P02", "P03"])]
    mixed = fit_mixed_models(few)
    assert mixed.pairwise is None
    assert mixed.skipped == ("pairwise: 3 participants; mixed models need at least 5.",)


def test_report_has_a_mixed_models_section(tmp_path):
    frame = pd.concat([pairwise_tidy(), ratings_tidy()], ignore_index=True)
    report = build_report(frame, ReportOptions())
    data = results_json(report)["mixed_models"]
    assert data["pairwise"]["apa"].startswith("Wald χ²(3)")
    assert [m["question"] for m in data["ordinal"]] == ["clarity"]
    assert data["ordinal"][0]["proportional_odds"]["holds"] is True
    assert data["linear"][0]["residual_sd"] > 0
    written = write_report(report, frame, tmp_path, draw_figures=False)
    assert {"mixed_effects.tex", "mixed_random.csv", "mixed_contrasts.md"} <= set(written)
    html = (tmp_path / "report.html").read_text()
    assert "<h2>Mixed models</h2>" in html and "Proportional-odds check" in html
    # Issue 35: the template (report.html.j2) was not escaped: a raw "<" in "p < .001".
    assert "p &lt; .001" in html and "p < .001" not in html
    assert "\n8 items;" in html and "<td>4|5</td>" in html
    assert "\\toprule" in (tmp_path / "mixed_effects.tex").read_text()
    effects = pd.read_csv(tmp_path / "mixed_effects.csv")
    assert set(effects["model"]) == {
        "Mixed-effects Bradley–Terry (logistic)",
        "Cumulative-link mixed model (proportional odds, logit)",
        "Linear mixed model",
    }
    linear = effects[effects["model"].eq("Linear mixed model")]
    assert set(linear["test"]) == {"t"} and linear["df"].gt(0).all()
    assert set(effects["test"]) == {"z", "t"}
    random = pd.read_csv(tmp_path / "mixed_random.csv")
    profiled = random[random["model"].eq("Linear mixed model")]
    assert (profiled["ci_low"] <= profiled["sd"]).all() and (
        profiled["sd"] <= profiled["ci_high"]
    ).all()


def test_mixed_models_can_be_turned_off():
    report = build_report(pairwise_tidy(), ReportOptions(mixed_models=False))
    assert results_json(report)["mixed_models"] is None


def test_factor_solves_and_takes_the_log_determinant():
    """The Schur-complement path agrees with numpy on an SPD matrix (the sparse one:
    test_mixed_sparse.py)."""
    from analysis.mixed.factor import Blocks, Factor

    rng = np.random.default_rng(5)
    k, r = 30, 6
    coupling = rng.normal(0, 0.3, (k, r))
    matrix = np.block(
        [
            [np.diag(rng.uniform(2, 4, k)), coupling],
            [coupling.T, np.eye(r) * 10 + 0.1],
        ]
    )
    rhs = rng.normal(size=(k + r, 3))
    expected_logdet = np.linalg.slogdet(matrix)[1]
    blocks = Blocks(np.diag(matrix)[:k], matrix[:k, k:], matrix[k:, k:])
    factor = Factor(blocks)
    assert factor.logdet == pytest.approx(expected_logdet)
    assert factor.solve(rhs) == pytest.approx(np.linalg.solve(matrix, rhs))
    assert factor.solve(rhs[:, 0]) == pytest.approx(np.linalg.solve(matrix, rhs[:, 0]))


def test_the_report_never_prints_negative_zero():
    """Issue 35: a strength printed as "-0.00" in the HTML report."""
    from analysis.outputs import _number

    assert (_number(-0.001, 2), _number(-0.5, 2), _number(None)) == ("0.00", "-0.50", "–")


def test_a_continuous_scale_gets_the_linear_model_only():
    """Issue 57: a slider's 0–100 exported as an ordinal rating got a cumulative-link
    model with a threshold between every pair of values; the ``scale`` column says which
    model a question's ratings take."""
    from analysis.tidy import check_responses, rating_scale

    frame = ratings_tidy()
    slider = frame.assign(
        question="slider",
        rating=frame["rating"].astype(float) * 20 - 7,
        scale="continuous",
    )
    points = frame.assign(scale="ordinal")
    both = check_responses(pd.concat([points, slider], ignore_index=True))
    assert (
        rating_scale(both, "slider") == "continuous" and rating_scale(both, "clarity") == "ordinal"
    )
    assert rating_scale(frame, "clarity") == "ordinal"  # no scale column: points
    mixed = fit_mixed_models(both)
    assert [m.question for m in mixed.ordinal] == ["clarity"]
    assert [m.question for m in mixed.linear] == ["clarity", "slider"]
    with pytest.raises(TidyFormatError, match="scale 'interval' is not one of ordinal, continuous"):
        check_responses(slider.assign(scale="interval"))
    with pytest.raises(TidyFormatError, match="question 'slider' has rating rows on more than"):
        mixed_scales = slider.copy()
        mixed_scales.loc[mixed_scales.index[:3], "scale"] = "ordinal"
        check_responses(mixed_scales)
