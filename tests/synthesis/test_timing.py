"""Test the word-timing representation and the Constant / Normalized constant models."""

import json

import pytest

from synthesis.timing import (
    TimingError,
    WordTiming,
    constant_timing,
    normalized_constant_timing,
)


def test_constant_model_numbers():
    """Seed 000 §4.3: 243 ms holds, the last 800 ms; 250 ms transitions."""
    timing = constant_timing("heaven")
    assert timing.letters == tuple("HEAVEN")
    assert timing.hold_ms == (243.0,) * 5 + (800.0,)
    assert timing.transition_ms == (250.0,) * 5
    assert timing.total_ms == 243 * 5 + 800 + 250 * 5
    assert timing.condition == "constant" and "Huenerfauth" in timing.metadata["source"]
    assert constant_timing("A").hold_ms == (800.0,)


def test_normalized_constant_lasts_as_long_as_its_reference():
    reference = WordTiming(tuple("ARREST"), (90, 80, 120, 100, 85, 160), (200, 150, 230, 210, 190))
    normalized = normalized_constant_timing("ARREST", reference)
    assert normalized.total_ms == pytest.approx(reference.total_ms)
    assert normalized.condition == "normalized"
    constant = constant_timing("ARREST")
    ratios = [n / c for n, c in zip(normalized.hold_ms, constant.hold_ms, strict=True)]
    assert max(ratios) == pytest.approx(min(ratios))  # one factor for the whole word
    with pytest.raises(ValueError, match="for ARREST, not HEAVEN"):
        normalized_constant_timing("HEAVEN", reference)


def test_timing_checks_its_shape_and_values():
    with pytest.raises(TimingError, match="3 letters need 3 holds, not 2"):
        WordTiming(tuple("ABC"), (1, 2), (1, 1))
    with pytest.raises(TimingError, match="3 letters need 2 transitions, not 1"):
        WordTiming(tuple("ABC"), (1, 2, 3), (1,))
    with pytest.raises(TimingError, match="positive"):
        WordTiming(tuple("AB"), (1, -2), (1,))


def test_round_trips_through_json_and_names_bad_files():
    timing = constant_timing("DAVID").scaled(0.5)
    again = WordTiming.from_dict(json.loads(json.dumps(timing.to_dict())))
    assert again == timing and again.metadata["scale"] == 0.5
    assert list(timing.hold_starts_ms()) == [0.0, 246.5, 493.0, 739.5, 986.0]
    with pytest.raises(TimingError, match="Not a word timing"):
        WordTiming.from_dict({"word": "A"})
    broken = timing.to_dict()
    del broken["hold_ms"]
    with pytest.raises(TimingError, match="lacks 'hold_ms'"):
        WordTiming.from_dict(broken)
