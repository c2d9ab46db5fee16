"""Golden tests of seed 002's DOF reduction (§4): irrelevance, rmsd1/rmsd2, rebuild, chains."""

import numpy as np
import pytest

from synthesis.hands import (
    apply_reduction,
    dof_counts,
    find_reduction,
    rebuild,
    reconstruction_error_deg,
    rmsd_matrices,
    standardise,
)


def smooth_curves(rng, frames: int, count: int, scale_deg: float = 20.0) -> np.ndarray:
    """Return independent smooth random curves (band-limited: a few sines each)."""
    t = np.arange(frames) / 30.0
    curves = np.zeros((frames, count))
    for k in range(count):
        for _ in range(4):
            frequency, phase = rng.uniform(0.1, 1.5), rng.uniform(0, 2 * np.pi)
            curves[:, k] += rng.normal(0, scale_deg / 2) * np.sin(2 * np.pi * frequency * t + phase)
    return curves


def test_rebuild_keeps_mean_and_sd_with_either_sign():
    """Seed 002 §4.2 by hand: b = [0, 1, 2] (mean 1, sd √(2/3)), a with mean 5, sd 2."""
    b = np.array([0.0, 1.0, 2.0])
    a = np.array([5 - 2 * np.sqrt(1.5), 5.0, 5 + 2 * np.sqrt(1.5)])
    z = (b - 1) / np.sqrt(2 / 3)
    np.testing.assert_allclose(rebuild(a, b, +1), z * 2 + 5)
    np.testing.assert_allclose(rebuild(a, b, -1), -z * 2 + 5)
    np.testing.assert_allclose(rebuild(a, b, +1), a)  # a is exactly b's positive image
    assert rebuild(a, np.ones(3), 1).tolist() == [5.0] * 3


def test_rmsd_metrics_match_their_definition():
    rng = np.random.default_rng(0)
    curves = rng.normal(size=(50, 4))
    rmsd1, rmsd2 = rmsd_matrices(curves)
    z = standardise(curves)
    for i in range(4):
        for j in range(4):
            assert rmsd1[i, j] == pytest.approx(
                np.sqrt(np.mean((z[:, i] - z[:, j]) ** 2)), abs=1e-6
            )
            assert rmsd2[i, j] == pytest.approx(
                np.sqrt(np.mean((z[:, i] + z[:, j]) ** 2)), abs=1e-6
            )


def test_irrelevant_curves_become_their_mean():
    curves = np.column_stack([np.linspace(0, 0.5, 30), np.linspace(0, 40, 30)])
    reduction = find_reduction(curves, ["still", "moving"], range_deg=1.0, rmsd=None)
    assert reduction.constant == {"still": pytest.approx(0.25)}
    reduced = apply_reduction(curves, reduction)
    np.testing.assert_allclose(reduced[:, 0], 0.25)
    np.testing.assert_array_equal(reduced[:, 1], curves[:, 1])
    assert reduction.dof_count == 1


def test_chains_resolve_to_the_root_controller():
    """b follows c, a follows b inversely: a is rebuilt from c with the sign composed."""
    rng = np.random.default_rng(1)
    c = 30 * np.sin(np.linspace(0, 6, 200))
    b = 0.8 * c + rng.normal(0, 0.6, 200)
    a = -0.5 * b + rng.normal(0, 0.3, 200)
    reduction = find_reduction(np.column_stack([a, b, c]), ["a", "b", "c"], 1.0, 0.3)
    found = {(r.dependent, r.controller, r.sign) for r in reduction.relations}
    assert found == {("a", "c", -1), ("b", "c", 1)}
    assert reduction.free == ("c",)


def test_a_synthetic_hand_with_planted_redundancy_gives_exactly_those_relations():
    """Spec 05 acceptance: digits driven from others with known sign and noise."""
    rng = np.random.default_rng(7)
    names = [f"dof{k}" for k in range(25)]
    curves = smooth_curves(rng, 900, 25)
    planted = {("dof3", "dof10", 1): 0.7, ("dof4", "dof10", -1): 0.5, ("dof20", "dof2", -1): 0.9}
    for (dependent, controller, sign), slope in planted.items():
        source = curves[:, names.index(controller)]
        noise = rng.normal(0, 0.05 * source.std(), len(source))
        curves[:, names.index(dependent)] = sign * slope * source + 12.0 + noise
    curves[:, 24] = 50 + rng.uniform(-0.3, 0.3, 900)  # under 1° of range: irrelevant
    reduction = find_reduction(curves, names, range_deg=1.0, rmsd=0.3)
    found = {(r.dependent, r.controller, r.sign) for r in reduction.relations}
    assert found == set(planted)
    assert set(reduction.constant) == {"dof24"}
    assert reduction.dof_count == 25 - 1 - 3
    errors = reconstruction_error_deg(curves, apply_reduction(curves, reduction))
    assert errors[names.index("dof3")] < 0.1 * curves[:, 3].std()
    assert errors[[names.index(n) for n in reduction.free]].max() == 0


def test_dof_counts_fall_step_by_step():
    rng = np.random.default_rng(2)
    curves = smooth_curves(rng, 300, 10)
    curves[:, 1] = curves[:, 0] * 0.9 + rng.normal(0, 0.5, 300)
    curves[:, 2] = 10 + rng.uniform(-2, 2, 300)  # range under 5°, over 1°
    counts = [count for *_, count in dof_counts(curves, [f"c{k}" for k in range(10)])]
    assert counts == sorted(counts, reverse=True) and counts[0] == 10 and counts[-1] <= 8
