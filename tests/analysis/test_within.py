"""Multiplicity corrections: Holm's step-down adjustment agrees with statsmodels'."""

import numpy as np
import pytest
from statsmodels.stats.multitest import multipletests

from analysis.within import adjust, holm


def test_holm_matches_statsmodels():
    rng = np.random.default_rng(4)
    for size in (1, 2, 6, 15):
        p = rng.random(size) ** 3
        assert holm(p) == pytest.approx(multipletests(p, method="holm")[1], abs=1e-15)


def test_holm_keeps_ties_and_caps_at_one():
    p = [0.04, 0.01, 0.04, 0.5, 0.3, 0.9]
    assert list(holm(p)) == pytest.approx(multipletests(p, method="holm")[1], abs=1e-15)
    assert list(holm(p)) == pytest.approx([0.2, 0.06, 0.2, 1.0, 0.9, 1.0])


@pytest.mark.parametrize("method", ["holm", "bonferroni", "fdr_bh"])
def test_every_correction_agrees_with_statsmodels(method):
    p = [0.002, 0.03, 0.04, 0.2]
    assert adjust(p, method) == pytest.approx(list(multipletests(p, method=method)[1]))


def test_an_unknown_correction_is_named():
    with pytest.raises(ValueError, match="Unknown correction 'sidak'"):
        adjust([0.1], "sidak")
