"""The fingerspelling timing models a study compares (spec 02; seed 000 ch. 4).

The timing names are listed here and nowhere else: ``simple`` (equal holds), ``constant``
(Huenerfauth's 243/800 ms holds and 250 ms transitions), ``normalized`` (constant at the
Variable model's length), ``variable`` (naïve Bayes holds, pose-distance transitions) and
``mocap`` (the performance as performed).
"""

from __future__ import annotations

import json
from collections.abc import Mapping
from pathlib import Path
from typing import TYPE_CHECKING, Any

from synthesis.fingerspelling.alphabets import DEFAULT_ALPHABET
from synthesis.techniques.parameters import ClipError, Parameter
from synthesis.techniques.registry import Technique
from synthesis.timing.constant import HOLD_MS, LAST_HOLD_MS, TRANSITION_MS
from synthesis.timing.recordings import MODEL_TIMINGS

if TYPE_CHECKING:
    from synthesis.techniques.request import Build

TIMINGS = ("mocap", *MODEL_TIMINGS, "simple")
DEFAULT_TIMING = "simple"
LABELS = {
    "simple": "simple (equal holds)",
    "constant": "Constant",
    "normalized": "Normalized constant (Constant scaled to the Variable model's length)",
    "variable": "Variable (naïve Bayes holds, pose-distance transitions)",
    "mocap": "Motion capture (the performance as performed)",
}


def variable_model(values):
    """Return the Variable model *values* name (the published one by default)."""
    from synthesis.timing import VariableModel, published_model

    return VariableModel.read(values["model"]) if values["model"] else published_model()


def _check(values) -> None:
    alphabet = values.get("alphabet", DEFAULT_ALPHABET)
    if values["timing"] in ("variable", "normalized") and alphabet != DEFAULT_ALPHABET:
        raise ClipError(
            f"timing {values['timing']!r} uses the Variable model, fitted to ASL "
            f"fingerspelling: with the {alphabet!r} alphabet, use timing 'simple' or "
            "'constant'."
        )
    if values["timing"] == "mocap" and values["source"] == "alphabet" and not values["timing_file"]:
        raise ClipError(
            "timing 'mocap' plays a performance as performed: set source to 'recording' "
            "(give --recording FILE.bvh of the word) or 'simulated' (or --simulate SEED "
            "for a simulated one)."
        )


def _read_timing_file(path: str, word: str):
    from synthesis.timing import WordTiming

    timing = WordTiming.from_dict(json.loads(Path(path).read_text("utf-8")))
    if timing.word != word:
        raise ClipError(f"{path} times {timing.word}, not {word}.")
    return timing


def word_timing(values, text: str, performance=None):
    """Return the timing *values* choose for the word *text* (a performance's own for mocap)."""
    from synthesis.fingerspelling.spelling import simple_timing, word_letters
    from synthesis.fingerspelling.word_timing import TimingError
    from synthesis.timing import constant_timing, normalized_constant_timing

    alphabet = values.get("alphabet", DEFAULT_ALPHABET)
    word = "".join(word_letters(text, alphabet))
    if values["timing_file"]:
        return _read_timing_file(values["timing_file"], word)
    timing = values["timing"]
    constant = {
        "hold_ms": values["hold_ms"],
        "last_hold_ms": values["last_hold_ms"],
        "transition_ms": values["transition_ms"],
    }
    if timing == "mocap":
        # As performed: the holds only describe it, and a recording whose holds cannot
        # be found still plays (None).
        try:
            return performance.extraction.timing
        except TimingError:
            return None
    if timing == "constant":
        return constant_timing(word, **constant)
    if timing in ("variable", "normalized"):
        variable = variable_model(values).timing(word)
        if timing == "variable":
            return variable
        return normalized_constant_timing(word, variable, **constant)
    return simple_timing(text, alphabet)


def _summary(values) -> str:
    if values["timing_file"]:
        return f"the timing saved in {values['timing_file']}"
    words = LABELS[values["timing"]]
    if values["timing"] in ("constant", "normalized"):
        words += (
            f" ({values['hold_ms']:g} ms holds, the last {values['last_hold_ms']:g} ms, "
            f"{values['transition_ms']:g} ms transitions)"
        )
    if values["timing"] in ("variable", "normalized"):
        words += f"; Variable model {values['model'] or 'the built-in one'}, {_provenance(values)}"
    return words


def _provenance(values) -> str:
    from synthesis.fingerspelling.word_timing import TimingError

    try:
        return variable_model(values).provenance()
    except (OSError, TimingError) as error:
        return f"not readable here ({error})"


def trained_on_simulated(values: Mapping[str, Any]) -> bool:
    """Return whether *values* time the words with a Variable model trained on
    simulated holds (the built-in one, or a file that says so)."""
    from synthesis.fingerspelling.word_timing import TimingError

    if values.get("timing_file") or values.get("timing") not in ("variable", "normalized"):
        return False
    try:
        return variable_model({"model": values.get("model", "")}).simulated
    except (OSError, TimingError):
        return False  # a model file not readable here says so in the description


def _apply(build: Build) -> Build:
    values = build.request.parameters
    return build.but(timing=word_timing(values, build.request.text, build.performance))


def _ms(name: str, default: float, help: str) -> Parameter:
    return Parameter(name, "float", default, help, minimum=1, maximum=10_000, units="ms")


TECHNIQUE = Technique(
    name="timing",
    chooses_content=True,
    label="Timing model",
    kinds=frozenset({"word"}),
    parameters=(
        Parameter(
            "timing",
            "choice",
            DEFAULT_TIMING,
            "How long each letter is held and each transition takes.",
            choices=TIMINGS,
            labels=LABELS,
        ),
        _ms("hold_ms", HOLD_MS, "Constant and Normalized: each letter's hold but the last."),
        _ms("last_hold_ms", LAST_HOLD_MS, "Constant and Normalized: the last letter's hold."),
        _ms("transition_ms", TRANSITION_MS, "Constant and Normalized: each transition."),
        Parameter(
            "model",
            "file",
            "",
            "A trained Variable model (JSON; python -m "
            "synthesis.timing train); empty: the one built from published statistics.",
        ),
        Parameter("timing_file", "file", "", "A word timing saved as JSON, used instead."),
    ),
    source="seed 000 §4.2–4.3",
    order=20,
    apply=_apply,
    check=_check,
    summary=_summary,
)
