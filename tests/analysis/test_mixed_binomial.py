"""Binomial data with trials in the mixed model (issue 56, item 8), against glmer.

Reference: tests/analysis/reference/binomial_trials.json, written with its data set
(binomial_trials.csv: 30 participants × 12 items × 2 conditions, 3–9 trials each) by
binomial_trials.R with Debian's R 4.2.2 and lme4 1.1-31:
``glmer(cbind(correct, trials − correct) ~ condition + (1 | participant) + (1 | item))``
with tolPwrss = 1e-13 (glmer's PIRLS converged, test_mixed_reference.py says why).
"""

import json

import numpy as np
import pandas as pd
import pytest

from analysis.mixed import Binomial, Component, MixedProblem, fit_laplace
from analysis.mixed.common import codes
from tests.analysis.mixed_data import REFERENCE

R = json.loads((REFERENCE / "binomial_trials.json").read_text())


def _problem(data: pd.DataFrame) -> MixedProblem:
    participant, people = codes(data["participant"])
    item, items = codes(data["item"])
    return MixedProblem(
        y=data["correct"].to_numpy(float),
        X=np.column_stack([np.ones(len(data)), (data["condition"] == "on").to_numpy(float)]),
        fixed_names=("(Intercept)", "conditionon"),
        components=(
            Component.from_codes("participant", "participant", participant, people),
            Component.from_codes("item", "item", item, items),
        ),
        family=Binomial(data["trials"].to_numpy()),
    )


def test_counts_with_trials_fit_as_glmer_fits_them():
    fit = fit_laplace(_problem(pd.read_csv(REFERENCE / "binomial_trials.csv")))
    assert fit.converged
    assert dict(zip(fit.names, fit.params, strict=True)) == {
        name: pytest.approx(value, abs=1e-5) for name, value in R["fixed"].items()
    }
    # Measured: estimates within 3e-8, SEs 2.4e-6, SDs 3.3e-7, log-likelihood 6e-12.
    ses = dict(zip(fit.names, np.sqrt(np.diag(fit.cov)), strict=True))
    assert ses == {name: pytest.approx(value, rel=1e-4) for name, value in R["se"].items()}
    assert fit.sd == pytest.approx([R["sd"]["participant"], R["sd"]["item"]], rel=1e-4)
    # The log-likelihood includes log C(trials, correct), as R's does.
    assert fit.loglik == pytest.approx(R["loglik"], abs=1e-6)


def test_trials_equal_to_one_are_the_bernoulli_model():
    from analysis.mixed import Bernoulli

    eta = np.linspace(-3, 3, 7)
    y = np.array([0, 1, 1, 0, 1, 0, 1], float)
    one = Binomial(np.ones(7)).derivatives(eta, y, np.zeros(0))
    bernoulli = Bernoulli().derivatives(eta, y, np.zeros(0))
    for field in ("loglik", "gradient", "weight"):
        np.testing.assert_allclose(getattr(one, field), getattr(bernoulli, field))


def test_impossible_counts_are_refused():
    with pytest.raises(ValueError, match="whole numbers of at least 1"):
        Binomial(np.array([3.0, 0.0]))
    with pytest.raises(ValueError, match="from 0 to the trials"):
        Binomial(np.array([3.0, 4.0])).extra_start(np.array([4.0, 1.0]))
