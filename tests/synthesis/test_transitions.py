"""Golden tests of seed 001's transition formulas: DCT descriptor, skewing, joins."""

import numpy as np
import pytest
from scipy.fft import dct
from scipy.interpolate import BSpline, CubicHermiteSpline, make_splrep

from synthesis.transitions import (
    basis_peaks,
    dct_ii,
    gap_descriptor,
    hermite_points,
    join_bspline,
    join_tangent,
    linear_transition,
    rmse_deg,
    scale_values,
    simple_hermite_transition,
    skew_bspline,
    skew_tangents,
    skew_values,
    window_tangent,
)


def test_dct_ii_is_the_seeds_sum_and_half_of_scipys():
    """X_k = Σ_n x_n cos(π/N (n + ½) k) (seed 001 Eq. 3.2), against the sum and scipy."""
    x = np.random.default_rng(1).normal(size=10)
    n = np.arange(10)
    by_hand = [np.sum(x * np.cos(np.pi / 10 * (n + 0.5) * k)) for k in range(3)]
    np.testing.assert_allclose(dct_ii(x), by_hand, rtol=1e-12)
    np.testing.assert_allclose(dct_ii(x), dct(x, type=2)[:3] / 2, rtol=1e-12)
    assert dct_ii(np.full(10, 2.0))[0] == pytest.approx(20.0)  # X_0 is the sum


def test_the_descriptor_has_42_numbers_curve_by_curve():
    rng = np.random.default_rng(2)
    before, after = rng.normal(size=(25, 7)), rng.normal(size=(12, 7))
    descriptor = gap_descriptor(before, after)
    assert descriptor.shape == (42,)
    # Curve 3: its 3 coefficients into the gap, then its 3 out of it.
    np.testing.assert_allclose(descriptor[18:21], dct_ii(before[-10:, 3]))
    np.testing.assert_allclose(descriptor[21:24], dct_ii(after[:10, 3]))
    with pytest.raises(ValueError, match="needs 10 frames on each side"):
        gap_descriptor(before[:5], after)


def test_skewing_lands_exactly_on_the_signs_values():
    x = np.linspace(0, 1, 50)
    y = 0.5 - 0.5 * np.cos(2 * np.pi * x) + 0.1 * x  # ends near where it starts
    y = (y - y.min()) / (y.max() - y.min())
    skewed = skew_values(y, x, delta_total=0.8, v0=0.3, v1=-0.2)
    assert skewed[0] == pytest.approx(0.3, abs=1e-15)
    assert skewed[-1] == pytest.approx(-0.2, abs=1e-15)
    # The shape is kept: what is taken off is a straight line in x.
    residual = skewed - 0.8 * (y - y[0])
    np.testing.assert_allclose(np.diff(residual, 2), 0, atol=1e-12)


def test_scaling_instead_of_skewing_explodes_when_the_curve_returns(tmp_path):
    """Seed 001 Fig. 4.3: with yN ≈ y0, Δv / Δy blows the curve up; skewing does not."""
    x = np.linspace(0, 1, 50)
    y = np.sin(np.pi * x) + 1e-4 * x  # out and back: yN − y0 = 1e-4
    scaled = scale_values(y, v0=0.0, v1=0.1)
    skewed = skew_values(y, x, delta_total=0.5, v0=0.0, v1=0.1)
    assert np.max(np.abs(scaled)) > 100  # a thousand times the gap
    assert np.max(np.abs(skewed)) < 0.6


def test_skewed_tangents_are_the_skewed_curves_derivative():
    """Eq. 3.9–3.10: a Hermite segment skewed point by point and by its tangents agree."""
    x = np.array([0.0, 0.4, 1.0])
    y = np.array([0.0, 1.0, 0.3])
    slopes = np.array([2.0, 0.5, -1.0])
    tangents = np.column_stack([np.ones(3), slopes])
    duration, delta_total, v0, v1 = 0.6, 0.9, 0.2, 0.7
    skewed = skew_tangents(tangents, y[0], y[-1], delta_total, v0, v1, duration)
    curve = CubicHermiteSpline(
        x * duration, skew_values(y, x, delta_total, v0, v1), skewed[:, 1] / skewed[:, 0]
    )
    original = CubicHermiteSpline(x, y, slopes)
    fine = np.linspace(0, 1, 200)
    np.testing.assert_allclose(
        curve(fine * duration),
        skew_values(original(fine), fine, delta_total, v0, v1),
        atol=1e-12,
    )


def test_basis_peaks_and_the_b_spline_skew_on_coefficients():
    """Eq. 3.11–3.12 on the seed's Figure 3.7 knots, then on a fitted smoothing spline."""
    knots = np.array([0, 0, 0, 0.5, 1, 1, 1.0])
    peaks = basis_peaks(knots, 2)
    # N_0 and N_3 peak at the ends; N_1 at 1/3 (its maximum 2/3), N_2 at 2/3 by symmetry.
    np.testing.assert_allclose(peaks, [0, 1 / 3, 2 / 3, 1], atol=1e-6)
    x = np.linspace(0, 1, 60)
    spline = make_splrep(x, np.sin(3 * x) + 0.2 * x, s=0.01)
    skewed = skew_bspline(spline, v0=-0.4, v1=1.3)
    assert isinstance(skewed, BSpline)
    assert skewed(0.0) == pytest.approx(-0.4, abs=1e-9)
    assert skewed(1.0) == pytest.approx(1.3, abs=1e-9)


def test_the_join_turns_to_the_signs_slope_and_shrinks_by_the_angle():
    """Eq. 3.16: r' = r (π − Δθ)/π, θ' = the sign's angle (here in the curve's own unit)."""
    aligned = join_tangent(np.array([1.0, 1.0]), sign_slope=1.0, degrees_per_unit=1.0)
    np.testing.assert_allclose(aligned, [1.0, 1.0])
    turned = join_tangent(np.array([2.0, 0.0]), sign_slope=np.inf, degrees_per_unit=1.0)
    np.testing.assert_allclose(turned, [0.0, 1.0], atol=1e-12)  # a quarter turn: half r = 2
    back = join_tangent(np.array([0.0, 1.0]), sign_slope=0.0, degrees_per_unit=1.0)
    np.testing.assert_allclose(back, [0.5, 0.0], atol=1e-12)


def test_the_join_measures_the_turn_in_the_papers_frame_by_degree_units():
    """Issue 38: seed 001 plots curves in frames × degrees. A tangent at −45° there (−1°
    a frame) turned to a sign rising 1° a frame turns 90° and keeps half its length; in
    radians the same tangents look flat and the shrink did nothing."""
    one_degree = np.radians(1.0)
    turned = join_tangent(np.array([1.0, -one_degree]), sign_slope=one_degree)
    np.testing.assert_allclose(turned, [0.5, 0.5 * one_degree], rtol=1e-12)
    in_radians = join_tangent(np.array([1.0, -one_degree]), one_degree, degrees_per_unit=1.0)
    shrunk = np.hypot(*in_radians) / np.hypot(1.0, one_degree)
    assert shrunk == pytest.approx(1 - 2 * np.arctan(one_degree) / np.pi)  # 1 %, not half


def test_the_bspline_join_leaves_and_arrives_along_the_signs_slopes():
    """Eq. 3.17: c₂ and c_{N−1} move so the ends' tangents meet the signs' directions;
    the ends stay where the skew put them."""
    x = np.linspace(0, 1, 40)
    spline = make_splrep(x, 0.3 + 0.2 * np.sin(3 * x), k=3, s=1e-4)
    duration, slope_in, slope_out = 39.0, 0.012, -0.02
    joined = join_bspline(spline, slope_in, slope_out, duration)
    velocity = joined.derivative()
    assert velocity(0.0) / duration == pytest.approx(slope_in, rel=1e-9)
    assert velocity(1.0) / duration == pytest.approx(slope_out, rel=1e-9)
    assert joined(0.0) == pytest.approx(spline(0.0)) and joined(1.0) == pytest.approx(spline(1.0))
    middle = slice(2, -2)
    np.testing.assert_array_equal(joined.c[middle], spline.c[middle])  # only c₂, c_{N−1}


def test_the_window_tangent_averages_the_last_slopes():
    values = np.array([0.0, 0.1, 0.3, 0.6, 1.0])
    assert window_tangent(values, 2) == pytest.approx((0.3 + 0.4) / 2)
    with pytest.raises(ValueError, match="needs 5 values"):
        window_tangent(values[:3], 4)


def test_hermite_basis_meets_its_points_and_tangents():
    """Seed 001 Eq. 5.2 at s = 0 and 1, and its derivative there."""
    p0, p1, t0, t1 = [0.0, 1.0], [4.0, 3.0], [1.0, 2.0], [2.0, -1.0]
    ends = hermite_points(p0, p1, t0, t1, np.array([0.0, 1.0]))
    np.testing.assert_allclose(ends, [p0, p1])
    h = 1e-6
    start = (hermite_points(p0, p1, t0, t1, np.array([h])) - ends[:1]) / h
    np.testing.assert_allclose(start[0], t0, atol=1e-4)


def test_the_baselines_join_the_signs():
    line = linear_transition(0.0, 1.0, 9)
    np.testing.assert_allclose(line, np.arange(1, 10) / 10)
    # Simple Hermite: its first and last steps follow the signs' slopes.
    curve = simple_hermite_transition(0.0, 0.05, 1.0, -0.02, 40)
    assert curve.shape == (40,)
    assert curve[0] - 0.0 == pytest.approx(0.05, abs=0.01)
    assert 1.0 - curve[-1] == pytest.approx(-0.02, abs=0.01)
    # With the slope of the straight line it is that line.
    slope = 1.0 / 41
    np.testing.assert_allclose(
        simple_hermite_transition(0.0, slope, 1.0, slope, 40),
        linear_transition(0.0, 1.0, 40),
        atol=1e-3,
    )
    assert rmse_deg(np.radians([1.0, 2.0]), np.radians([1.0, 4.0])) == pytest.approx(np.sqrt(2))
