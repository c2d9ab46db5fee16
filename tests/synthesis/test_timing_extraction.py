"""Test finding holds and transitions in recordings generated with a known timing.

The recordings are simulated captures (synthesis.timing.simulate): the word spelled with
a timing sampled from the published model, plus sensor noise (0.3° RMS to 10 Hz) and a
slow wander of every joint (1° RMS to 1.5 Hz), so the hand never quite stops.
"""

import numpy as np
import pytest

from synthesis.timing import (
    CaptureNoise,
    ExtractionError,
    WordTiming,
    extract,
    published_model,
    simulate_recording,
)

STUDY_WORDS = ("GUITAR", "HEAVEN", "ARREST", "ELEPHANT", "PSYCHIATRY", "DAVID", "MICHAEL",
               "VICTOR")  # fmt: skip


def _hold_errors(rate_hz: float, noise: CaptureNoise, lead_ms: float = 250.0) -> np.ndarray:
    """Return |found − true| hold durations (ms) over three takes of every study word."""
    model = published_model()
    errors = []
    for seed in range(3):
        rng = np.random.default_rng(seed)
        for word in STUDY_WORDS:
            motion, truth = simulate_recording(word, rng, model, rate_hz=rate_hz, noise=noise,
                                               lead_ms=lead_ms)  # fmt: skip
            found = extract(motion, word)
            assert found.timing.letters == truth.letters
            bounds = found.hold_bounds_s
            assert np.all(bounds[1:, 0] >= bounds[:-1, 1])  # holds never overlap
            errors.extend(np.abs(np.array(found.timing.hold_ms) - truth.hold_ms))
    return np.array(errors)


def test_recovers_known_holds_from_noisy_recordings():
    """Measured: 156 of 162 holds (96 %) within one frame at 60 fps; median error 1.7 ms.
    The misses are mostly doubled letters, whose 7° slide is near the wander's size."""
    errors = _hold_errors(60.0, CaptureNoise())
    assert np.mean(errors <= 1000 / 60) >= 0.9
    assert np.median(errors) < 4.0


def test_recovers_noise_free_holds_to_a_fraction_of_a_frame():
    errors = _hold_errors(60.0, CaptureNoise(sensor_deg=0.0, wander_deg=0.0))
    assert np.all(errors <= 1000 / 60)
    assert np.median(errors) < 2.0


def test_recordings_at_120_fps_and_without_a_lead_in():
    """Measured: 96 % (120 fps) and 95 % (no rest before or after the word) within a
    60 fps frame."""
    assert np.mean(_hold_errors(120.0, CaptureNoise()) <= 1000 / 60) >= 0.9
    assert np.mean(_hold_errors(60.0, CaptureNoise(), lead_ms=0.0) <= 1000 / 60) >= 0.9


def test_path_letters_get_their_whole_path_as_the_hold():
    timing = WordTiming(tuple("JAZZ"), (400, 90, 450, 420), (220, 260, 150))
    motion, truth = simulate_recording("JAZZ", np.random.default_rng(5), timing=timing)
    found = extract(motion, "JAZZ")
    assert np.allclose(found.timing.hold_ms, truth.hold_ms, atol=1000 / 60)
    assert found.timing.metadata["rate_hz"] == 60


def test_a_recording_of_another_word_is_a_clear_error():
    rng = np.random.default_rng(1)
    motion, _ = simulate_recording("CAT", rng)
    with pytest.raises(ExtractionError, match="fewer times than the word has letters"):
        extract(motion, "PSYCHIATRY")
    with pytest.raises(ExtractionError, match="empty"):
        extract(motion, " ")
    with pytest.raises(ExtractionError, match="too few to hold"):
        extract(motion.with_values(motion.values[:5]), "CAT")
    recording, _ = simulate_recording("DAVID", rng)
    with pytest.raises(ExtractionError, match="do not look like the letters of MOVIE"):
        extract(recording, "MOVIE")
