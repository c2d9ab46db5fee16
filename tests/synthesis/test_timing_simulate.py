"""Test simulated captures: sampled timings and capture noise."""

import numpy as np
import pytest

from synthesis.fingerspelling.alphabet import AlphabetError
from synthesis.rigs.hand import HandModel
from synthesis.timing import CaptureNoise, published_model, sample_timing, simulate_recording
from synthesis.timing.bayes import CLASSES_MS


def test_sampled_timings_vary_like_takes_and_repeat_by_seed():
    model = published_model()
    first = sample_timing(model, "ELEPHANT", np.random.default_rng(3))
    again = sample_timing(model, "ELEPHANT", np.random.default_rng(3))
    other = sample_timing(model, "ELEPHANT", np.random.default_rng(4))
    assert first == again and first != other
    assert first.condition == "mocap" and first.metadata["simulated"] is True
    assert set(first.hold_ms) <= set(CLASSES_MS)  # holds are the classifier's classes
    takes = [sample_timing(model, "ELEPHANT", np.random.default_rng(s)) for s in range(200)]
    transitions = np.array([t.transition_ms for t in takes])
    assert np.all(transitions >= model.transitions.minimum_ms)
    # Around the regression line with the published residual spread (≈ 54 ms).
    predicted = model.timing("ELEPHANT").transition_ms
    assert np.allclose(transitions.mean(axis=0), predicted, atol=15)
    assert 40 < transitions.std(axis=0).mean() < 70


def test_capture_noise_has_the_asked_size_and_band():
    noise = CaptureNoise(sensor_deg=0.5, sensor_hz=8.0, wander_deg=0.0)
    sample = noise.sample(3000, 4, 120.0, np.random.default_rng(0))
    assert np.degrees(sample.std(axis=0)) == pytest.approx([0.5] * 4, rel=1e-6)
    spectrum = np.abs(np.fft.rfft(sample, axis=0)) ** 2
    freqs = np.fft.rfftfreq(3000, 1 / 120)
    assert spectrum[freqs > 30].sum() < 0.01 * spectrum.sum()  # low-passed
    silent = CaptureNoise(sensor_deg=0.0, wander_deg=0.0)
    assert not np.any(silent.sample(10, 3, 60.0, np.random.default_rng(0)))


def test_a_simulated_recording_is_a_bvh_ready_hand_motion():
    motion, timing = simulate_recording("CAT", np.random.default_rng(0))
    assert motion.skeleton.names == HandModel().skeleton.names
    assert motion.rate_hz == 60
    assert motion.duration_s == pytest.approx(timing.total_ms / 1000 + 0.7, abs=1 / 60)
    with pytest.raises(AlphabetError, match="'3' is not a letter"):
        simulate_recording("C3T", np.random.default_rng(0))
