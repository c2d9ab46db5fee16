"""Compare the mixed models with R's lme4 and ordinal on data with known effects.

Reference values: tests/analysis/reference/mixed_reference.json, written by
tests/analysis/reference/make_mixed_reference.py (data generated there, seeded) running
mixed_reference.R with R 4.2.2, lme4 1.1-31 and ordinal 2022.11-16. The issue asks for
fixed effects within 2 % and random-effect SDs within 10 %; the Laplace fits agree far
closer, so the tolerances here are tighter (0.5 % and 1 %), and standard errors and
log-likelihoods are checked too.
"""

import json

import numpy as np
import pandas as pd
import pytest

from analysis.mixed import (
    Component,
    MixedProblem,
    fit_laplace,
    linear_mixed,
    mixed_bradley_terry,
    ordinal_mixed,
    proportional_odds_test,
)
from analysis.mixed.common import codes
from tests.analysis.mixed_data import REFERENCE, pairwise_tidy, ratings_tidy

R = json.loads((REFERENCE / "mixed_reference.json").read_text())
close = pytest.approx


def _fixed(name: str) -> dict[str, dict]:
    return {row["name"]: row for row in R[name]["fixed"]}


def test_pairwise_intercepts_match_glmer():
    result = mixed_bradley_terry(pairwise_tidy(), ["a", "b", "c", "d"], random_strengths=False)
    expected = _fixed("pairwise_intercepts")
    assert result.position.estimate == close(expected["(Intercept)"]["estimate"], rel=5e-3)
    assert result.position.se == close(expected["(Intercept)"]["se"], rel=1e-2)
    for effect in result.effects:
        row = expected[f"x_{effect.name}"]
        assert effect.estimate == close(row["estimate"], rel=5e-3)
        assert effect.se == close(row["se"], rel=1e-2)
    sds = {r["group"]: r["sd"] for r in R["pairwise_intercepts"]["random"]}
    assert {c.name: c.sd for c in result.random} == {
        "participant": close(sds["participant"], rel=1e-2),
        "item": close(sds["item"], rel=1e-2),
    }
    assert result.loglik == close(R["pairwise_intercepts"]["loglik"], abs=1e-2)


def test_random_slope_matches_glmer():
    """A random slope for one condition (its own variance), as glmer's (0 + x_b | participant)."""
    data = pd.read_csv(REFERENCE / "mixed_pairwise.csv")
    participant, levels = codes(data["participant"])
    item, items = codes(data["item"])
    problem = MixedProblem(
        y=data["first"].to_numpy(float),
        X=np.column_stack([np.ones(len(data)), data[["x_b", "x_c", "x_d"]]]),
        fixed_names=("(Intercept)", "x_b", "x_c", "x_d"),
        components=(
            Component.from_codes("participant", "participant", participant, levels),
            Component.from_codes(
                "x_b", "participant", participant, levels, values=data[["x_b"]].to_numpy()
            ),
            Component.from_codes("item", "item", item, items),
        ),
    )
    fit = fit_laplace(problem)
    expected = _fixed("pairwise_slope")
    for name, estimate, se in zip(fit.names, fit.params, np.sqrt(np.diag(fit.cov)), strict=True):
        assert estimate == close(expected[name]["estimate"], rel=5e-3)
        assert se == close(expected[name]["se"], rel=1e-2)
    assert fit.sd == close([r["sd"] for r in R["pairwise_slope"]["random"]], rel=1e-2)
    # The optimum is at least as good as lme4's (bobyqa stops a little short here).
    assert fit.loglik >= R["pairwise_slope"]["loglik"] - 1e-3


def test_ordinal_matches_clmm():
    result = ordinal_mixed(ratings_tidy(), "clarity", ["a", "b", "c"])
    expected = _fixed("ordinal")
    for effect in result.effects:
        row = expected[f"condition{effect.name}"]
        assert effect.estimate == close(row["estimate"], rel=5e-3)
        assert effect.se == close(row["se"], rel=1e-2)
    for threshold in result.thresholds:
        row = expected[threshold.name]
        assert threshold.estimate == close(row["estimate"], rel=5e-3)
        assert threshold.se == close(row["se"], rel=1e-2)
    sds = {r["group"]: r["sd"] for r in R["ordinal"]["random"]}
    assert {c.name: c.sd for c in result.random} == {k: close(v, rel=1e-2) for k, v in sds.items()}
    assert result.loglik == close(R["ordinal"]["loglik"], abs=1e-2)


def test_linear_matches_lmer():
    result = linear_mixed(ratings_tidy(), "clarity", ["a", "b", "c"])
    expected = _fixed("linear")
    for effect in result.effects:
        row = expected[f"condition{effect.name}"]
        assert effect.estimate == close(row["estimate"], rel=1e-6)
        assert effect.se == close(row["se"], rel=1e-3)
    sds = {r["group"]: r["sd"] for r in R["linear"]["random"]}
    assert {c.name: c.sd for c in result.random} == {
        "participant": close(sds["participant"], rel=1e-3),
        "item": close(sds["item"], rel=1e-3),
    }
    assert result.residual_sd == close(sds["Residual"], rel=1e-3)
    assert result.loglik == close(R["linear"]["loglik"], abs=1e-3)


@pytest.mark.parametrize(
    ("name", "key"),
    [("mixed_ratings.csv", "nominal_proportional"), ("mixed_nonproportional.csv", "nominal")],
)
def test_proportional_odds_check_matches_nominal_test(name, key):
    data = pd.read_csv(REFERENCE / name)
    result = proportional_odds_test(data, ["a", "b", "c"])
    assert result.statistic == close(R[key]["statistic"], rel=1e-5)
    assert result.df == R[key]["df"]
    assert result.pvalue == close(R[key]["pvalue"], rel=1e-4)
    assert result.holds is (key == "nominal_proportional")


CONVERGED = json.loads((REFERENCE / "glmer_converged.json").read_text())


@pytest.mark.parametrize("name", ["pairwise_intercepts", "pairwise_slope"])
def test_laplace_standard_errors_are_glmers_with_its_pirls_converged(name):
    """Issue 56, item 4: glmer's default standard errors differ from ours by 0.1–0.4 %
    here (1.3 % on cbpp) because its PIRLS stops at tolPwrss = 1e-7 and its log det L lags
    one iteration; with tolPwrss = 1e-13 (glmer_converged.R) they agree to 1e-4 (measured
    within 2e-5), as do the estimates and the log-likelihood."""
    data = pd.read_csv(REFERENCE / "mixed_pairwise.csv")
    participant, levels = codes(data["participant"])
    item, items = codes(data["item"])
    components = [Component.from_codes("participant", "participant", participant, levels)]
    if name == "pairwise_slope":
        values = data[["x_b"]].to_numpy()
        components.append(
            Component.from_codes("x_b", "participant", participant, levels, values=values)
        )
    components.append(Component.from_codes("item", "item", item, items))
    problem = MixedProblem(
        y=data["first"].to_numpy(float),
        X=np.column_stack([np.ones(len(data)), data[["x_b", "x_c", "x_d"]]]),
        fixed_names=("(Intercept)", "x_b", "x_c", "x_d"),
        components=tuple(components),
    )
    fit = fit_laplace(problem)
    converged = CONVERGED[name]["converged"]
    ses = dict(zip(fit.names, np.sqrt(np.diag(fit.cov)), strict=True))
    assert ses == {key: close(value, rel=1e-4) for key, value in converged["se"].items()}
    assert fit.loglik == close(converged["loglik"], abs=1e-5)
    # The default glmer's differ by more than the acceptance's 1e-3 somewhere: the reason
    # this test exists.
    default = CONVERGED[name]["default"]["se"]
    assert max(abs(ses[key] / value - 1) for key, value in default.items()) > 1e-3
