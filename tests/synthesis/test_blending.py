"""Test seed 004's concatenation with linear blending (§4.1.3) and its C⁰-only velocity."""

import numpy as np
import pytest

from synthesis.transitions import blend_offsets, blend_signs, velocity_jumps


def test_each_sign_starts_one_overlap_before_the_last_ends():
    """E'_n = Σ_{i≤n} D_i − n·a: every overlap shortens the sequence by a."""
    assert list(blend_offsets([100, 80, 120], 20)) == [0, 80, 140]
    with pytest.raises(ValueError, match="at least 40 frames"):
        blend_offsets([100, 30], 20)


def test_weights_sum_to_one_and_signs_keep_their_bodies():
    rest = np.zeros(3)
    first = np.vstack(
        [np.linspace(rest, [1, 1, 1], 10), np.ones((30, 3)), np.linspace([1, 1, 1], rest, 10)]
    )
    second = np.vstack(
        [
            np.linspace(rest, [-1, 0, 2], 10),
            np.tile([-1, 0, 2], (30, 1)),
            np.linspace([-1, 0, 2], rest, 10),
        ]
    )
    blended = blend_signs([first, second], overlap=10)
    assert blended.shape == (50 + 50 - 10, 3)
    np.testing.assert_allclose(blended[10:40], first[10:40])  # first body untouched
    np.testing.assert_allclose(blended[50:80], second[10:40])  # second body untouched
    # In the overlap: (a − k)/(a + 1) of the decay plus (k + 1)/(a + 1) of the attack.
    k = np.arange(10)[:, None]
    expected = ((10 - k) * first[40:50] + (k + 1) * second[:10]) / 11
    np.testing.assert_allclose(blended[40:50], expected)
    constant = blend_signs([np.ones((30, 2)), np.ones((30, 2))], overlap=10)
    np.testing.assert_allclose(constant, 1.0)


def test_linear_blending_is_continuous_but_its_velocity_jumps():
    """Seed 004 §5: C⁰ only — positions join, velocities change abruptly at the overlap."""
    t = np.linspace(0, 1, 60)[:, None]
    rising = np.hstack([np.sin(np.pi * t), t])  # moving at both ends
    falling = np.hstack([np.cos(np.pi * t), 1 - t])
    blended = blend_signs([rising, falling], overlap=15)
    assert np.max(np.abs(np.diff(blended, axis=0))) < 0.2  # no jump in position
    jumps = velocity_jumps(blended, rate_hz=60.0)
    smooth = velocity_jumps(rising, rate_hz=60.0)
    # The overlap's ends (frames 45 and 60) carry the largest changes of velocity.
    assert np.max(jumps) > 3 * np.max(smooth)
    assert int(np.argmax(jumps)) + 1 in range(43, 62)
