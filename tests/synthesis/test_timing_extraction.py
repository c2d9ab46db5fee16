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

STUDY_WORDS = ("GUITAR", "HEAVEN", "ARREST", "ELEPHANT", "PSYCHIATRY", "DAVID", "MICHAEL", "VICTOR")


def _hold_errors(
    rate_hz: float, noise: CaptureNoise, lead_ms: float = 250.0, takes: int = 3
) -> np.ndarray:
    """Return |found − true| hold durations (ms) over *takes* takes of every study word."""
    model = published_model()
    errors = []
    for seed in range(takes):
        rng = np.random.default_rng(seed)
        for word in STUDY_WORDS:
            motion, truth = simulate_recording(
                word, rng, model, rate_hz=rate_hz, noise=noise, lead_ms=lead_ms
            )
            found = extract(motion, word)
            assert found.timing.letters == truth.letters
            bounds = found.hold_bounds_s
            assert np.all(bounds[1:, 0] >= bounds[:-1, 1])  # holds never overlap
            errors.extend(np.abs(np.array(found.timing.hold_ms) - truth.hold_ms))
    return np.array(errors)


def test_recovers_known_holds_from_noisy_recordings():
    """Acceptance of issue 4. Measured: 149 of 162 holds (92 %) within one frame at
    60 fps, median error 1.7 ms; noise-free 96 %, median 0.8 ms (routed transitions,
    whose moves turn round a finger, make most of the misses)."""
    errors = _hold_errors(60.0, CaptureNoise())
    assert np.mean(errors <= 1000 / 60) >= 0.9
    assert np.median(errors) < 4.0


def test_recordings_at_120_fps_and_without_a_lead_in():
    """Measured over three takes: 95 % (120 fps) and 86 % (no rest before or after the
    word: the first and last holds have one move to fit, not two) within a 60 fps frame."""
    assert np.mean(_hold_errors(120.0, CaptureNoise(), takes=1) <= 1000 / 60) >= 0.85
    assert np.mean(_hold_errors(60.0, CaptureNoise(), lead_ms=0.0, takes=1) <= 1000 / 60) >= 0.8


def test_path_letters_get_their_path_as_the_hold():
    """J and Z are timed from arriving at their path's first pose to leaving its last;
    their paths turn, so this is coarser than a still letter's hold (measured here:
    within 135 ms; no study word has J or Z)."""
    timing = WordTiming(tuple("JAZZ"), (400, 90, 450, 420), (220, 260, 150))
    motion, truth = simulate_recording("JAZZ", np.random.default_rng(5), timing=timing)
    found = extract(motion, "JAZZ")
    assert found.timing.letters == truth.letters
    assert np.allclose(found.timing.hold_ms, truth.hold_ms, atol=150)
    assert abs(found.timing.hold_ms[1] - 90) < 1000 / 60  # the A between them
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
    with pytest.raises(ExtractionError, match="do not look like the letters of HOUSE"):
        extract(recording, "HOUSE")
