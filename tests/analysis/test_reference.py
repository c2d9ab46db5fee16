"""Compare the within-subject tests with an independent implementation to 1e-8.

Reference values: tests/analysis/reference/within_subject.json, written by
tests/analysis/reference/make_reference.py with pingouin 0.7.0 (d_z by hand).
"""

import json
from pathlib import Path

import pandas as pd
import pytest

from analysis import friedman, paired_ttests, rm_anova, wilcoxon_tests

REFERENCE = json.loads((Path(__file__).parent / "reference" / "within_subject.json").read_text())
DATASETS = REFERENCE["datasets"]
close = pytest.approx


def _scores(dataset) -> pd.DataFrame:
    return pd.DataFrame(dataset["scores"], index=dataset["subjects"])


@pytest.mark.parametrize("dataset", DATASETS, ids=lambda d: f"{len(d['subjects'])}-subjects")
def test_rm_anova_matches_reference(dataset):
    expected = dataset["expected"]["rm_anova"]
    result = rm_anova(_scores(dataset))
    assert result.statistic == close(expected["F"], rel=1e-8)
    assert (result.df_num, result.df_den) == (expected["df_num"], expected["df_den"])
    assert result.pvalue == close(expected["p"], rel=1e-8)
    assert result.eta_p2 == close(expected["eta_p2"], rel=1e-8)
    assert result.epsilon_gg == close(expected["epsilon_gg"], rel=1e-8)
    assert result.pvalue_gg == close(expected["p_gg"], rel=1e-8)
    assert result.mauchly_w == close(expected["mauchly_w"], rel=1e-8)
    assert result.mauchly_pvalue == close(expected["mauchly_p"], rel=1e-8)


@pytest.mark.parametrize("dataset", DATASETS, ids=lambda d: f"{len(d['subjects'])}-subjects")
def test_paired_ttests_match_reference(dataset):
    results = paired_ttests(_scores(dataset), "holm")
    for result, expected in zip(results, dataset["expected"]["posthoc"], strict=True):
        assert (result.a, result.b) == (expected["a"], expected["b"])
        assert result.statistic == close(expected["t"], rel=1e-8)
        assert result.df == expected["df"]
        assert result.pvalue == close(expected["p"], rel=1e-8)
        assert result.pvalue_adjusted == close(expected["p_holm"], rel=1e-8)
        assert result.dz == close(expected["dz"], rel=1e-8)


@pytest.mark.parametrize("dataset", DATASETS, ids=lambda d: f"{len(d['subjects'])}-subjects")
def test_friedman_matches_reference(dataset):
    expected = dataset["expected"]["friedman"]
    result = friedman(_scores(dataset))
    assert result.statistic == close(expected["Q"], rel=1e-8)
    assert result.df == expected["df"]
    assert result.pvalue == close(expected["p"], rel=1e-8)
    assert result.kendall_w == close(expected["W"], rel=1e-8)


@pytest.mark.parametrize("dataset", DATASETS, ids=lambda d: f"{len(d['subjects'])}-subjects")
def test_wilcoxon_effect_size_matches_reference(dataset):
    """The rank-biserial r (pingouin's); V and p follow R's conventions, which pingouin's
    W = min(W⁺, W⁻) does not: test_wilcoxon_r.py checks them against R itself."""
    results = wilcoxon_tests(_scores(dataset), "none")
    for result, expected in zip(results, dataset["expected"]["wilcoxon"], strict=True):
        assert (result.a, result.b) == (expected["a"], expected["b"])
        assert result.rank_biserial == close(expected["rank_biserial"], rel=1e-8)


def test_sphericity_violation_is_reported_in_the_apa_string():
    violated = next(d for d in DATASETS if d["expected"]["rm_anova"]["mauchly_p"] < 0.05)
    assert "Greenhouse–Geisser ε = 0.55" in rm_anova(_scores(violated)).apa()
