"""Test finding holds and transitions in recordings generated with a known timing."""

import numpy as np
import pytest

from synthesis.hand import HandModel
from synthesis.motion import Motion
from synthesis.spelling import spell
from synthesis.timing import ExtractionError, WordTiming, extract

STUDY_WORDS = ("GUITAR", "HEAVEN", "ARREST", "ELEPHANT", "PSYCHIATRY", "DAVID", "MICHAEL",
               "VICTOR")  # fmt: skip
FRAME_MS = 1000 / 60


def _recording(word: str, rng: np.random.Generator) -> tuple[Motion, WordTiming]:
    """Spell *word* with a random known timing (a longer last hold) as a 60 fps BVH motion."""
    holds = rng.uniform(60, 160, len(word))
    holds[-1] += 150
    timing = WordTiming(tuple(word), tuple(holds), tuple(rng.uniform(120, 300, len(word) - 1)))
    model = HandModel()
    dofs = spell(word, rate_hz=60, timing=timing, lead_ms=300)
    return Motion(model.skeleton, model.channel_values(dofs), 1 / 60), timing


def test_recovers_known_holds_of_the_study_words():
    """Measured on these noise-free recordings: 50 of 54 holds (93 %) within one frame at
    60 fps (sub-frame boundaries). Issue 4 asks ≥ 90 % with capture noise as well: with
    0.3° of low-passed noise it is about 70 % so far."""
    rng = np.random.default_rng(0)
    errors = []
    for word in STUDY_WORDS:
        motion, truth = _recording(word, rng)
        found = extract(motion, word)
        assert found.timing.letters == truth.letters
        assert all(a[1] <= b[0] for a, b in zip(found.hold_frames, found.hold_frames[1:],
                                                 strict=False))  # fmt: skip
        errors.extend(np.abs(np.array(found.timing.hold_ms) - truth.hold_ms))
    errors = np.array(errors)
    assert np.mean(errors <= FRAME_MS) >= 0.9
    assert np.median(errors) < 8


def test_a_recording_of_another_word_is_a_clear_error():
    motion, _ = _recording("CAT", np.random.default_rng(1))
    with pytest.raises(ExtractionError, match="PSYCHIATRY has 10 letters"):
        extract(motion, "PSYCHIATRY")
    with pytest.raises(ExtractionError, match="empty"):
        extract(motion, " ")
    recording, _ = _recording("DAVID", np.random.default_rng(2))
    with pytest.raises(ExtractionError, match="do not look like the letters of TAKEDAVID"):
        extract(recording, "TAKEDAVID")
