"""The Wilcoxon signed-rank tests against R's own ``wilcox.test(paired = TRUE)``.

Reference: tests/analysis/reference/wilcoxon_r.json, written by wilcoxon.R (in that
folder) with Debian's R: the within-subject reference data sets (10 and 24 subjects, no
ties: exact p) and datasets::sleep (a zero and ties: the normal approximation with
continuity correction, V = 45, p = 0.009091; issue 56 found .0039 here, the exact
permutation p of min(W⁺, W⁻)).
"""

import json
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from analysis import wilcoxon_tests
from analysis.within import wilcoxon_test

REFERENCE = Path(__file__).parent / "reference"
R = json.loads((REFERENCE / "wilcoxon_r.json").read_text())
WITHIN = json.loads((REFERENCE / "within_subject.json").read_text())["datasets"]


@pytest.mark.parametrize("number", range(len(WITHIN)))
def test_v_and_p_are_rs_on_the_reference_data_sets(number):
    dataset = WITHIN[number]
    scores = pd.DataFrame(dataset["scores"], index=dataset["subjects"])
    ours = wilcoxon_tests(scores, "none")
    for result, expected in zip(ours, R["within_subject"][number], strict=True):
        assert (result.a, result.b) == (expected["a"], expected["b"])
        assert result.statistic == expected["V"]
        assert result.pvalue == pytest.approx(expected["p"], rel=1e-10)
        exact = "exact" in expected["method"] or "continuity" not in expected["method"]
        assert (result.method == "exact") == exact


def test_sleep_with_a_zero_and_ties_is_the_normal_approximation():
    sleep = R["sleep"]
    result = wilcoxon_test(np.array(sleep["a_values"]), np.array(sleep["b_values"]), ("2", "1"))
    assert result.statistic == sleep["V"] == 45
    assert result.pvalue == pytest.approx(sleep["p"], rel=1e-10)
    assert "continuity" in sleep["method"]
    assert result.method == "normal approximation, continuity-corrected"
    assert result.apa().startswith("2 vs 1: V = 45, p = .009 (normal approximation")
