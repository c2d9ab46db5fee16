"""Data a model cannot support get a named note or error, never a number that looks like one.

Each case is one the issue 34 review found: a bare numpy warning, z = 7.5e15, F = −2.8,
a LinAlgError, an empty power curve, or nan.
"""

import numpy as np
import pandas as pd
import pytest

from analysis.anova import rm_anova
from analysis.mixed import (
    MixedProblem,
    fit_laplace,
    linear_mixed,
    mixed_bradley_terry,
    ordinal_mixed,
)
from analysis.mixed.lmm import fit_lmm
from analysis.power import Effects, PlannedDesign, Trial, binomial_n, binomial_power, power_curve
from analysis.tidy import TidyFormatError
from tests.analysis import crossed_data


def test_every_rating_the_same_is_refused_by_name():
    frame = crossed_data.ratings_tidy(1).assign(rating=3.0)
    with pytest.raises(TidyFormatError, match="every rating is 3, so there is no variation"):
        linear_mixed(frame, "q", ["off", "on"])


@pytest.mark.parametrize("model", [linear_mixed, ordinal_mixed])
def test_ratings_determined_by_condition_are_refused_by_name(model):
    frame = crossed_data.ratings_tidy(1)
    frame = frame.assign(rating=np.where(frame["condition_a"].eq("on"), 4.0, 2.0))
    with pytest.raises(
        TidyFormatError, match=r"fully determined by condition \(off: every rating 2; on: every"
    ):
        model(frame, "q", ["off", "on"])


@pytest.mark.parametrize("model", [linear_mixed, ordinal_mixed])
def test_ratings_determined_by_participant_are_refused_by_name(model):
    """Each participant one rating for every clip: the linear fit's residual SD went to 0
    and the profile CI's optimiser failed, sinking the whole report (found building a
    slider study, issue 57)."""
    frame = crossed_data.ratings_tidy(1)
    codes = frame["participant"].astype("category").cat.codes
    frame = frame.assign(rating=1.0 + codes % 5)
    with pytest.raises(TidyFormatError, match="every participant gave one rating to every clip"):
        model(frame, "q", ["off", "on"])


def test_a_duplicated_fixed_effect_column_is_dropped_and_named():
    problem = crossed_data.binary_problem(1)
    twice = MixedProblem(
        y=problem.y,
        X=np.column_stack([problem.X, 2 * problem.X[:, 1]]),
        fixed_names=(*problem.fixed_names, "twice"),
        components=problem.components,
    )
    alone, fit = fit_laplace(problem), fit_laplace(twice)
    assert fit.dropped == ("twice",) and fit.names == problem.fixed_names
    assert "rank deficient so dropping 1 column / coefficient (twice)" in fit.checks[0]
    assert fit.params == pytest.approx(alone.params, abs=1e-6)
    linear = fit_lmm(
        MixedProblem(
            y=problem.y, X=twice.X, fixed_names=twice.fixed_names, components=problem.components
        )
    )
    assert linear.dropped == ("twice",) and len(linear.beta) == 2


def test_a_condition_never_shown_is_named():
    frame = crossed_data.pairwise_tidy(1)
    with pytest.raises(TidyFormatError, match="conditions d cannot be estimated"):
        mixed_bradley_terry(frame, ["a", "b", "c", "d"])


def test_separated_choices_get_a_note_not_a_test():
    frame = crossed_data.pairwise_tidy(1)
    # Whatever the order, "c" is always chosen when it is shown.
    with_c = frame["condition_a"].eq("c") | frame["condition_b"].eq("c")
    frame.loc[with_c, "chosen"] = "c"
    result = mixed_bradley_terry(frame, ["a", "b", "c"])
    assert any("separated by condition" in note and "c" in note for note in result.notes)


def test_rm_anova_on_constant_scores_says_so():
    result = rm_anova(pd.DataFrame({"a": [1.0] * 5, "b": [1.0] * 5, "c": [1.0] * 5}))
    assert np.isnan(result.statistic) and np.isnan(result.eta_p2)
    assert result.apa() == (
        "F not computed: Every subject's scores are the same at every level: "
        "there is no variance to test."
    )


def test_rm_anova_with_zero_error_variance_says_so():
    scores = pd.DataFrame({"a": [1.0, 2, 3, 4, 5], "b": [2.0, 3, 4, 5, 6], "c": [0.0, 1, 2, 3, 4]})
    result = rm_anova(scores)
    assert np.isnan(result.statistic)
    assert "error variance is zero" in result.apa()


def test_rm_anova_names_the_subjects_it_leaves_out():
    scores = pd.DataFrame(
        {"a": [1.0, 2, 3, 4, 5], "b": [2.0, 1, 5, np.nan, 6]}, index=["p1", "p2", "p3", "p4", "p5"]
    )
    result = rm_anova(scores)
    assert result.nobs == 4
    assert result.notes == ("1 subject(s) without a score at every level are left out (p4).",)


def test_power_curve_of_a_rating_design_needs_thresholds():
    design = PlannedDesign("rating", ("a", "b"), ((Trial("S", "a", ""), Trial("S", "b", "")),), "q")
    with pytest.raises(ValueError, match="a rating design needs the scale's thresholds"):
        power_curve(design, Effects({"a": 0.0, "b": 0.5}), [10], simulations=2, workers=1)


@pytest.mark.parametrize(
    ("call", "message"),
    [
        (lambda: binomial_power(10, 1.2), "between 0 and 1, not 1.2"),
        (lambda: binomial_power(0, 0.6), "whole number ≥ 1, not 0"),
        (lambda: binomial_power(10, 0.6, alpha=1.5), "alpha must lie between 0 and 1"),
        (lambda: binomial_n(-0.1), "between 0 and 1, not -0.1"),
    ],
)
def test_closed_form_power_refuses_impossible_inputs(call, message):
    with pytest.raises(ValueError, match=message):
        call()


def test_power_planning_says_when_the_pilot_sd_is_on_the_boundary():
    """Set 5 (true SDs 0): the pilot's fit is singular, and the plan says what that means."""
    from analysis.power import effects_from_pilot

    pilot = mixed_bradley_terry(crossed_data.pairwise_tidy(5), ["a", "b", "c"])
    assert pilot.singular
    effects = effects_from_pilot(pilot)
    assert effects.sd_participant == 0.0
    assert "participant and item SDs sit on the boundary of zero" in effects.notes[0]
    trials = (Trial("W", "a", "b"), Trial("W", "c", "a"), Trial("W", "b", "c")) * 2
    design = PlannedDesign("pairwise", ("a", "b", "c"), (trials,))
    curve = power_curve(design, effects, [4], simulations=2, workers=1)
    assert "overstates power" in curve.summary()
