"""The sphericity corrections and d_z's interval against R's own numbers.

Reference: tests/analysis/reference/within_r.json, written by within_r.R (in that
folder) with Debian's R 4.2.2 on the within-subject reference data sets (10 subjects with
sphericity kept, 24 with it violated): ``anova.mlm(..., test = "Spherical")``'s
Greenhouse–Geisser and Huynh–Feldt epsilons (printed to 4 digits; Huynh–Feldt uncapped)
and their corrected p-values (full precision, epsilons capped at 1), and the exact 95 % CI
of d_z by root-finding on R's noncentral ``pt``.
"""

import json
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from analysis import paired_ttests, rm_anova
from analysis.within import dz_interval, paired_ttest, wilcoxon_test

REFERENCE = Path(__file__).parent / "reference"
R = json.loads((REFERENCE / "within_r.json").read_text())["within_subject"]
WITHIN = json.loads((REFERENCE / "within_subject.json").read_text())["datasets"]


def _scores(number: int) -> pd.DataFrame:
    dataset = WITHIN[number]
    return pd.DataFrame(dataset["scores"], index=dataset["subjects"])


@pytest.mark.parametrize("number", range(len(WITHIN)))
def test_greenhouse_geisser_and_huynh_feldt_are_rs(number):
    expected, result = R[number], rm_anova(_scores(number))
    assert result.statistic == pytest.approx(expected["F"], rel=1e-10)
    assert result.epsilon_gg == pytest.approx(expected["epsilon_gg"], abs=5e-5)
    assert result.epsilon_hf == pytest.approx(min(expected["epsilon_hf"], 1.0), abs=5e-5)
    assert result.pvalue_gg == pytest.approx(expected["p_gg"], rel=1e-9)
    assert result.pvalue_hf == pytest.approx(expected["p_hf"], rel=1e-9)


def test_the_violated_set_reports_both_corrections():
    violated = next(n for n in range(len(WITHIN)) if R[n]["epsilon_hf"] < 1)
    text = rm_anova(_scores(violated)).apa()
    assert "Greenhouse–Geisser ε" in text and "Huynh–Feldt ε" in text


@pytest.mark.parametrize("number", range(len(WITHIN)))
def test_dz_intervals_are_rs_noncentral_t_limits(number):
    ours = paired_ttests(_scores(number), "none")
    for result, expected in zip(ours, R[number]["dz"], strict=True):
        assert (result.a, result.b) == (expected["a"], expected["b"])
        assert result.dz == pytest.approx(expected["dz"], rel=1e-10)
        assert result.dz_ci == pytest.approx(expected["ci"], abs=1e-7)


def test_two_conditions_have_no_sphericity_test():
    scores = _scores(0).iloc[:, :2]
    result = rm_anova(scores)
    assert np.isnan(result.mauchly_w) and np.isnan(result.mauchly_pvalue)
    assert result.epsilon_gg == result.epsilon_hf == 1.0
    assert "ε" not in result.apa()


def test_a_pair_whose_differences_are_all_zero_has_no_wilcoxon_test():
    """R's wilcox.test gives V = 0 and p NA here; "W = 0, p = 1.000" would read as a test."""
    same = np.array([3.0, 4.0, 5.0])
    result = wilcoxon_test(same, same, ("a", "b"))
    assert np.isnan(result.statistic) and np.isnan(result.pvalue)
    assert result.apa() == "a vs b: V not computed (n = 3; every difference is zero)"
    ttest = paired_ttest(same, same, ("a", "b"))
    assert "not computed" in ttest.apa() and np.isnan(ttest.dz_ci[0])


@pytest.mark.parametrize("n", [2, 3, 5, 12, 40, 300])
def test_dz_intervals_are_finite_and_hold_the_estimate_wherever_they_are_asked(n):
    """nct's cdf returns NaN far from the root for some t and df (the report once
    stopped on it): every interval here is finite, ordered and holds d_z."""
    for dz in (-6.0, -1.7, -0.2, 0.0, 0.05, 0.9, 3.3, 8.0):
        low, high = dz_interval(dz, n)
        assert np.isfinite(low) and np.isfinite(high) and low < dz < high, (dz, n)
