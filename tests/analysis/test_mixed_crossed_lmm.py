"""The linear mixed model against lmer, lmerTest and anova() on 100 crossed designs.

Reference: tests/analysis/reference/crossed.R (R 4.2.2, lme4 1.1-31, lmerTest 3.1-3),
data crossed_within.csv.gz, fits crossed_fits.json. Before issue 34 the REML search
stopped at a false boundary in 47 of these sets (up to 9.9 log-likelihood units short).
Correlated slopes: lmer itself stops at a false boundary in 22 of the sets (a "failed to
converge … negative eigenvalue" warning, up to 1.7 units below our optimum; its θ,
evaluated by our criterion, gives its own log-likelihood to 1e-12), so estimates are
compared where both reach the same optimum (fixed effects and SEs to 1e-4, SDs to
0.1 %: the likelihood is that flat in them). Profile CIs: lme4 interpolates ζ by
splines, so lower limits near zero differ by up to 0.01; upper limits agree to 1e-3
(the residual SD's to 0.2 %).
"""

import numpy as np
import pandas as pd
import pytest

from analysis.mixed import linear_mixed
from analysis.mixed.common import codes
from analysis.mixed.lmm import fit_lmm
from analysis.mixed.problem import Component, MixedProblem
from analysis.tidy import TidyFormatError
from tests.analysis import crossed_data

# 100 reference sets fitted several ways: tens of seconds.
pytestmark = pytest.mark.slow

SETS = crossed_data.fits()["sets"]


def _singular_agrees(ours: bool, loglik: float, reference: dict) -> bool:
    if ours == reference["singular"]:
        return True
    lower = [t for t in reference["theta"] if t >= 0]
    return ours and min(lower) < 2e-3 and loglik >= reference["loglik"] - 1e-6


@pytest.fixture(scope="module")
def fitted():
    """Fit every set by REML (the default) and by ML through the public API."""
    out = {}
    for reference in SETS:
        frame = crossed_data.ratings_tidy(reference["set"], "numeric")
        sd_ci = reference["set"] <= 20
        out[reference["set"]] = (
            linear_mixed(frame, "q", ["off", "on"], sd_ci=sd_ci),
            linear_mixed(frame, "q", ["off", "on"], reml=False, sd_ci=False),
        )
    return out


@pytest.mark.parametrize("method", ["reml", "ml"])
def test_lmm_reaches_lmer(fitted, method):
    short, singular = [], []
    for reference in SETS:
        fit = fitted[reference["set"]][method == "ml"]
        r = reference[method]
        if fit.loglik < r["loglik"] - 0.01:
            short.append(reference["set"])
        if not _singular_agrees(fit.singular, fit.loglik, r):
            singular.append(reference["set"])
        assert fit.effects[0].estimate == pytest.approx(r["fixed"]["conditionon"], abs=1e-4)
        assert fit.effects[0].se == pytest.approx(r["se"]["conditionon"], abs=1e-4)
        assert fit.residual_sd == pytest.approx(r["residual_sd"], abs=1e-4)
        assert fit.converged
    assert short == [] and singular == []


@pytest.mark.parametrize("method", ["reml", "ml"])
def test_satterthwaite_matches_lmertest(fitted, method):
    for reference in SETS:
        fit = fitted[reference["set"]][method == "ml"]
        r = reference[method]
        effect = fit.effects[0]
        assert effect.df == pytest.approx(r["satterthwaite"]["df"]["conditionon"], rel=1e-3)
        assert effect.pvalue == pytest.approx(r["satterthwaite"]["pvalue"]["conditionon"], abs=1e-3)
        assert fit.statistic == pytest.approx(r["anova"]["F"], rel=1e-4)
        assert fit.den_df == pytest.approx(r["anova"]["df_den"], rel=1e-3)
        assert fit.pvalue == pytest.approx(r["anova"]["pvalue"], abs=1e-3)


def test_likelihood_ratio_matches_anova(fitted):
    for reference in SETS:
        test = fitted[reference["set"]][0].likelihood_ratio
        assert test.statistic == pytest.approx(reference["lr"]["statistic"], abs=1e-4)
        assert test.df == reference["lr"]["df"]
        assert test.pvalue == pytest.approx(reference["lr"]["pvalue"], abs=1e-4)
        assert test.loglik_reduced == pytest.approx(reference["lr"]["loglik_null"], abs=1e-5)


def test_profile_intervals_match_confint(fitted):
    for reference in SETS[:20]:
        fit = fitted[reference["set"]][0]
        profile = reference["reml"]["profile"]
        expected = [profile["sd_(Intercept)|participant"], profile["sd_(Intercept)|item"]]
        for component, (low, high) in zip(fit.random, expected, strict=True):
            assert component.ci[1] == pytest.approx(high, abs=1e-3)
            assert component.ci[0] == pytest.approx(low, abs=1e-2)
        assert fit.residual_sd_ci == pytest.approx(profile["sigma"], rel=2e-3)


def _slopes_problem(number: int) -> MixedProblem:
    data = crossed_data.within(number)
    X = np.column_stack([np.ones(len(data)), data["condition"].eq("on").to_numpy(float)])
    participant, levels = codes(data["participant"])
    item, items = codes(data["item"])
    return MixedProblem(
        y=data["numeric"].to_numpy(float),
        X=X,
        fixed_names=("(Intercept)", "conditionon"),
        components=(
            Component.from_codes(
                "participant",
                "participant",
                participant,
                levels,
                values=X,
                columns=("(Intercept)", "on"),
                correlated=True,
            ),
            Component.from_codes("item", "item", item, items),
        ),
    )


def test_correlated_slopes_match_lmer():
    same = 0
    for reference in SETS:
        fit = fit_lmm(_slopes_problem(reference["set"]))
        r = reference["slopes"]
        assert fit.loglik >= r["loglik"] - 0.01
        assert fit.criterion.profiled(np.array(r["theta"])) == pytest.approx(-2 * r["loglik"])
        if abs(fit.loglik - r["loglik"]) > 1e-6:
            continue
        same += 1
        assert fit.beta == pytest.approx(list(r["fixed"].values()), abs=1e-4)
        assert np.sqrt(np.diag(fit.cov)) == pytest.approx(list(r["se"].values()), abs=1e-4)
        sds = [r["sd"]["participant (Intercept)"], r["sd"]["participant conditionon"]]
        # The likelihood is flat in the SDs here: 1e-6 in log-likelihood moves them 1e-4.
        assert fit.sd == pytest.approx([*sds, r["sd"]["item (Intercept)"]], rel=1e-3, abs=2e-4)
        if not r["singular"]:
            correlation = r["sd"]["participant (Intercept) conditionon"]
            assert fit.correlations[0][3] == pytest.approx(correlation, abs=1e-3)
    assert same >= 70


def test_slopes_through_the_api_and_refused_where_not_identified():
    frame = crossed_data.ratings_tidy(2, "numeric")
    result = linear_mixed(frame, "q", ["off", "on"], slopes=True)
    assert result.formula == "q ~ condition + (1 + condition | participant) + (1 | item)"
    assert [c.column for c in result.random] == ["(Intercept)", "on", "(Intercept)"]
    assert len(result.correlations) == 1
    assert result.loglik >= SETS[1]["slopes"]["loglik"] - 0.01
    between = frame[~(frame["condition_a"].eq("on") & frame["participant"].isin(["P01", "P02"]))]
    between = pd.concat([between])
    with pytest.raises(TidyFormatError, match=r"rated every condition; 6 of 8 did"):
        linear_mixed(between, "q", ["off", "on"], slopes=True)
    automatic = linear_mixed(between, "q", ["off", "on"], slopes=None)
    assert "(1 | participant)" in automatic.formula
    assert any("Intercepts only" in note for note in automatic.notes)


def test_rounding_the_ratings_at_1e_10_does_not_move_the_fit():
    """The issue's symptom: noise in the last digits flipped a REML fit by 15 units."""
    for number in (1, 4, 7, 10, 13):
        frame = crossed_data.ratings_tidy(number, "numeric")
        exact = linear_mixed(frame, "q", ["off", "on"], sd_ci=False)
        rounded = linear_mixed(frame.assign(rating=frame["rating"].round(10)), "q", sd_ci=False)
        assert rounded.loglik == pytest.approx(exact.loglik, abs=1e-6)
        assert [c.sd for c in rounded.random] == pytest.approx(
            [c.sd for c in exact.random], abs=1e-4
        )
