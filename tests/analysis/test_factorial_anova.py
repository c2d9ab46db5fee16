"""The two-way within-subject ANOVA against R (issue 56, item 8).

Reference: tests/analysis/reference/factorial_r.json, written with its data set
(factorial.csv: 16 subjects × A (2 levels) × B (3), unequal cell variances so that B's
sphericity is rejected) by factorial_r.R with Debian's R 4.2.2: F, df and p per effect
from ``aov(y ~ A * B + Error(subject / (A * B)))``; Greenhouse–Geisser and Huynh–Feldt p
and Mauchly's test per effect from ``anova.mlm`` and ``mauchly.test`` with ``idata``.
"""

import json

import numpy as np
import pandas as pd
import pytest

from analysis.factorial import factorial_rm_anova
from tests.analysis.mixed_data import REFERENCE

R = json.loads((REFERENCE / "factorial_r.json").read_text())
DATA = pd.read_csv(REFERENCE / "factorial.csv")


def test_every_effect_is_rs():
    effects = {e.effect: e for e in factorial_rm_anova(DATA, "y", "subject", ("A", "B"))}
    assert set(effects) == {"A", "B", "A:B"}
    for name, expected in R.items():
        if name == "software":
            continue
        ours = effects[name]
        assert (ours.df_num, ours.df_den) == (expected["df_num"], expected["df_den"])
        for field, theirs in (
            ("statistic", "F"),
            ("pvalue", "p"),
            ("pvalue_gg", "p_gg"),
            ("pvalue_hf", "p_hf"),
        ):
            assert getattr(ours, field) == pytest.approx(expected[theirs], rel=1e-9), field
        if expected["df_num"] >= 2:
            assert ours.mauchly_w == pytest.approx(expected["mauchly_w"], rel=1e-9)
            assert ours.mauchly_pvalue == pytest.approx(expected["mauchly_p"], rel=1e-9)
        else:  # one df: R prints W = 1, p = 1; there is nothing to test
            assert np.isnan(ours.mauchly_w) and ours.epsilon_gg == ours.epsilon_hf == 1.0


def test_the_apa_line_names_the_corrections_where_sphericity_fails():
    effects = {e.effect: e for e in factorial_rm_anova(DATA, "y", "subject", ("A", "B"))}
    assert effects["B"].apa() == (
        "B: F(2, 30) = 1.94, p = .162, η²p = .11 (Greenhouse–Geisser ε = 0.58, p = .182; "
        "Huynh–Feldt ε = 0.60, p = .181)"
    )
    assert effects["A"].apa() == "A: F(1, 15) = 0.16, p = .692, η²p = .01"


def test_a_subject_missing_a_cell_is_left_out_and_named():
    short = DATA[~((DATA["subject"] == 3) & (DATA["A"] == "a2") & (DATA["B"] == "b3"))]
    effects = factorial_rm_anova(short, "y", "subject", ("A", "B"))
    assert all(e.nobs == 15 for e in effects)
    assert effects[0].notes == ("1 subject(s) without a value in every cell left out (3).",)
