"""Crossed designs too wide to eliminate participants first: the sparse path against R.

Reference: tests/analysis/reference/sparse_crossed.R (R 4.2.2, lme4 1.1-31, lmerTest 3.1-3,
ordinal 2022.11-16) simulated 150 participants each rating 24 of 400 items and making 24
forced choices on random items (InstEval's shape: each participant sees a few of many
items), and fitted lmer (REML, ML, Satterthwaite, profile CIs), clmm and glmer
(tolPwrss = 1e-12); sparse_crossed.json. The random-effects system here has 400 item
columns after the participants, so it is factored sparse in one fixed pattern
(analysis.mixed.cholesky), which the small designs of the other reference tests never
reach. Tolerances are those of the issue (56): 1e-4 relative, 1e-3 for Laplace SEs and
profile limits. Measured: every number within 9e-6 of R's but clmm's condition effect,
3.4e-5 (clmm stops on a gradient of 1e-3 or so; our log-likelihood is 5e-7 higher).
"""

import functools
import json

import numpy as np
import pandas as pd
import pytest

from analysis.mixed import linear_mixed, mixed_bradley_terry, ordinal_mixed
from analysis.mixed.cholesky import SparsePattern, StaleFactorError
from analysis.mixed.modes import ConditionalModes
from analysis.mixed.ordinal import ordinal_problem, rated_conditions
from tests.analysis.mixed_data import REFERENCE, pairwise_rows, rating_rows

R = json.loads((REFERENCE / "sparse_crossed.json").read_text())


@functools.cache
def _ratings(column: str) -> pd.DataFrame:
    data = pd.read_csv(REFERENCE / "sparse_ratings.csv.gz")
    return rating_rows(data, "q", column)


def test_the_reference_design_is_factored_sparse():
    data, order = rated_conditions(_ratings("rating"), "q", ["off", "on"])
    modes = ConditionalModes(ordinal_problem(data, order))
    assert not modes.blocked and modes.q == 550


def test_linear_mixed_model_matches_lmer_on_the_sparse_path():
    r = R["linear"]
    fit = linear_mixed(_ratings("numeric"), "q", ["off", "on"])
    effect = fit.effects[0]
    assert effect.estimate == pytest.approx(r["fixed"]["conditionon"], rel=1e-4)
    assert effect.se == pytest.approx(r["se"]["conditionon"], rel=1e-4)
    assert effect.df == pytest.approx(r["df"], rel=1e-4)
    assert fit.loglik == pytest.approx(r["loglik"], rel=1e-8)
    assert fit.residual_sd == pytest.approx(r["sd"]["Residual"], rel=1e-4)
    for component in fit.random:
        assert component.sd == pytest.approx(r["sd"][component.name], rel=1e-4)
        limits = r["ci"][f"sd_(Intercept)|{component.name}"]
        assert component.ci == pytest.approx(limits, rel=1e-3)
    assert fit.residual_sd_ci == pytest.approx(r["ci"]["sigma"], rel=1e-3)
    assert fit.likelihood_ratio.statistic == pytest.approx(r["lr"], rel=1e-4)
    assert fit.likelihood_ratio.loglik_full == pytest.approx(r["loglik_ml"], rel=1e-8)


def test_ordinal_mixed_model_matches_clmm_on_the_sparse_path():
    r = R["ordinal"]
    fit = ordinal_mixed(_ratings("rating"), "q", ["off", "on"])
    assert fit.loglik == pytest.approx(r["loglik"], rel=1e-8)
    assert fit.effects[0].estimate == pytest.approx(r["fixed"]["conditionon"], rel=1e-4)
    assert fit.effects[0].se == pytest.approx(r["se"]["conditionon"], rel=1e-3)
    cuts = [r["fixed"][name] for name in ("1|2", "2|3", "3|4", "4|5")]
    assert [t.estimate for t in fit.thresholds] == pytest.approx(cuts, rel=1e-4)
    for component in fit.random:
        assert component.sd == pytest.approx(r["sd"][component.name], rel=1e-3)


def test_mixed_bradley_terry_matches_glmer_on_the_sparse_path():
    r = R["pairwise"]
    pairs = pairwise_rows(pd.read_csv(REFERENCE / "sparse_pairs.csv.gz"))
    fit = mixed_bradley_terry(pairs, ["a", "b", "c"])
    assert fit.loglik == pytest.approx(r["loglik"], rel=1e-8)
    ours = [fit.position.estimate, *(e.estimate for e in fit.effects)]
    assert ours == pytest.approx(list(r["fixed"].values()), rel=1e-4)
    ses = [fit.position.se, *(e.se for e in fit.effects)]
    assert ses == pytest.approx(list(r["se"].values()), rel=1e-3)
    for component in fit.random:
        assert component.sd == pytest.approx(r["sd"][component.name], rel=1e-3)


def test_a_sparse_pattern_factors_solves_and_refuses_a_stale_factor():
    """LDLᵀ in a fixed pattern against numpy, refactored at a second matrix."""
    rng = np.random.default_rng(56)
    size = 40
    rows, cols = rng.integers(0, size, 120), rng.integers(0, size, 120)
    pattern = SparsePattern(rows, cols, size)
    raw = np.zeros(len(pattern.keys))
    raw[pattern.slots(rows, cols)] = rng.normal(0, 1, len(rows))
    symmetric = pattern.dense(raw)
    base = symmetric @ symmetric.T  # the product fills in: give it its own pattern
    dense_pattern = SparsePattern(*np.triu_indices(size), size)
    values = base[dense_pattern.rows, dense_pattern.cols]
    first = dense_pattern.factor(dense_pattern.identity_plus_scaled(values, np.ones(size)))
    matrix = base + np.eye(size)
    rhs = rng.normal(size=(size, 2))
    assert first.logdet == pytest.approx(np.linalg.slogdet(matrix)[1], rel=1e-12)
    assert first.solve(rhs) == pytest.approx(np.linalg.solve(matrix, rhs), rel=1e-9)
    scale = rng.uniform(0.5, 2, size)
    second = dense_pattern.factor(dense_pattern.identity_plus_scaled(values, scale))
    scaled = scale[:, None] * base * scale[None, :] + np.eye(size)
    assert second.logdet == pytest.approx(np.linalg.slogdet(scaled)[1], rel=1e-12)
    assert second.solve(rhs[:, 0]) == pytest.approx(np.linalg.solve(scaled, rhs[:, 0]), rel=1e-9)
    with pytest.raises(StaleFactorError):
        first.solve(rhs)
    with pytest.raises(np.linalg.LinAlgError):
        dense_pattern.factor(-values)
