"""Huenerfauth's Constant timing and its Normalized version (seed 000 §4.3, spec 02).

Constant: every letter held 243 ms, the last 800 ms for emphasis (seed 000 ref. 48);
every transition 250 ms, the mean of seed 000's recorded transitions (the reference does
not give one). Normalized constant: the same, scaled as a whole to another timing's
total duration (the Variable model's, in the study), so that only the rhythm differs.
"""

from synthesis.fingerspelling.word_timing import WordTiming

HOLD_MS = 243.0
LAST_HOLD_MS = 800.0
TRANSITION_MS = 250.0
SOURCE = "Huenerfauth 2009 (seed 000 ref. 48) holds; seed 000 §4.3 mean transition"


def constant_timing(
    word: str,
    hold_ms: float = HOLD_MS,
    last_hold_ms: float = LAST_HOLD_MS,
    transition_ms: float = TRANSITION_MS,
) -> WordTiming:
    """Return the Constant timing of *word* (Huenerfauth's durations unless given)."""
    letters = tuple(c.upper() for c in word if not c.isspace())
    holds = (float(hold_ms),) * (len(letters) - 1) + (float(last_hold_ms),) if letters else ()
    return WordTiming(
        letters,
        holds,
        (float(transition_ms),) * max(len(letters) - 1, 0),
        "constant",
        {"source": SOURCE},
    )


def normalized_constant_timing(word: str, reference: WordTiming, **durations_ms) -> WordTiming:
    """Return the Constant timing scaled to last exactly as long as *reference*.

    *durations_ms* are :func:`constant_timing`'s hold and transition durations.
    """
    constant = constant_timing(word, **durations_ms)
    if constant.letters != reference.letters:
        raise ValueError(f"The reference timing is for {reference.word}, not {constant.word}.")
    normalized = constant.scaled(reference.total_ms / constant.total_ms, "normalized")
    return WordTiming(
        normalized.letters,
        normalized.hold_ms,
        normalized.transition_ms,
        "normalized",
        {**normalized.metadata, "normalized_to": reference.condition},
    )
