"""Where a fingerspelled word's motion comes from: the engine's alphabet, a simulated
capture, or a recording (seed 000 §4.3: conditions retime one performance).

The rules a study applies to a word's own recording live here too, so that nothing
outside the registry knows which parameter means which motion: a condition retiming "a
recording" without naming a file takes each word's own; one retiming "a simulated
capture" does so where the word has a recording, so the simulated stand-in remains only
where none exists.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import TYPE_CHECKING, Any

from synthesis.fingerspelling.alphabets import DEFAULT_ALPHABET, alphabet_choices, alphabet_codes
from synthesis.techniques.parameters import ClipError, Parameter
from synthesis.techniques.registry import Technique
from synthesis.techniques.timing import DEFAULT_TIMING

if TYPE_CHECKING:
    from synthesis.techniques.request import Build

SOURCES = ("alphabet", "simulated", "recording")
# The performances a word's own recording replaces: a recording, or its simulated stand-in.
RETIMED_SOURCES = ("recording", "simulated")
# Stands for "each word's own recording" when a condition's parameters are checked or
# described; the real file is found when a clip is specified.
ITEM_RECORDING = "each word's own recording"


def uses_item_recording(parameters: Mapping[str, Any]) -> bool:
    """Return whether a condition with *parameters* retimes each word's own recording."""
    return parameters.get("source") == "recording" and not parameters.get("recording")


def takes_item_recording(parameters: Mapping[str, Any]) -> bool:
    """Return whether a word's own recording, where it has one, is the performance under
    *parameters* (a capture retimed without a file of its own)."""
    return parameters.get("source") in RETIMED_SOURCES and not parameters.get("recording")


def as_checked(parameters: Mapping[str, Any]) -> dict:
    """Return *parameters* as the registry checks them: a condition that retimes each
    word's own recording names it by :data:`ITEM_RECORDING`."""
    parameters = dict(parameters)
    if uses_item_recording(parameters):
        parameters["recording"] = ITEM_RECORDING
    return parameters


def with_recording(parameters: Mapping[str, Any], path: str) -> dict:
    """Return *parameters* with the recording at *path* as the performance."""
    return {**parameters, "source": "recording", "recording": path}


def is_simulated_stand_in(parameters: Mapping[str, Any]) -> bool:
    """Return whether a condition shows the simulated capture as it is (its own timing).

    That condition stands in for motion capture: it is labelled simulated exactly while
    some word of its study has no recording.
    """
    return parameters.get("source") == "simulated" and parameters.get("timing") == "mocap"


def retimes_recording(parameters: Mapping[str, Any]) -> bool:
    """Return whether a condition retimes its words' recordings (so their holds must be
    found), rather than only playing them as performed."""
    return (
        parameters.get("source") in RETIMED_SOURCES
        and parameters.get("timing", DEFAULT_TIMING) != "mocap"
    )


def _check(values) -> None:
    if values["source"] != "alphabet" and values["alphabet"] != DEFAULT_ALPHABET:
        # Captures are ASL: their holds are found by matching ASL's handshapes.
        raise ClipError(
            f"source {values['source']!r} is a capture of ASL fingerspelling: with the "
            f"{values['alphabet']!r} alphabet, set source to 'alphabet'."
        )
    if values["source"] == "recording" and not values["recording"]:
        raise ClipError(
            "source 'recording' needs the recording: set recording to a BVH or .pose file of "
            "the word (--recording FILE.bvh)."
        )
    if values["recording"] and values["source"] != "recording":
        raise ClipError(
            f"recording is set but source is {values['source']!r}: set source "
            "to 'recording' or leave recording empty."
        )


def _apply(build: Build) -> Build:
    from synthesis.techniques.timing import variable_model
    from synthesis.timing.recordings import Recording

    request, values = build.request, build.request.parameters
    if values["source"] == "simulated":
        # One performance per item, shared by its conditions: only the timing differs.
        performance = Recording.simulate(
            request.text, request.seed, variable_model(values), request.side, request.rate_hz
        )
        return build.but(performance=performance)
    if values["source"] == "recording":
        return build.but(
            performance=Recording.read(values["recording"], request.text, request.side)
        )
    return build


TECHNIQUE = Technique(
    name="source",
    chooses_content=True,
    label="Performance",
    kinds=frozenset({"word"}),
    parameters=(
        Parameter(
            "source",
            "choice",
            "alphabet",
            "What the conditions animate: the engine's alphabet spelled with the timing, a "
            "simulated capture (timing sampled from the Variable model plus capture noise; "
            "labelled simulated), or a recording that every timing retimes.",
            choices=SOURCES,
            labels={
                "alphabet": "the engine's alphabet",
                "simulated": "a simulated capture",
                "recording": "a recording",
            },
        ),
        Parameter(
            "recording", "file", "", "A BVH or .pose recording of the word (source 'recording')."
        ),
        Parameter(
            "alphabet",
            "choice",
            DEFAULT_ALPHABET,
            "The manual alphabet the word is spelled in (a study sets it for all its words).",
            choices=alphabet_codes(),
            labels=dict(alphabet_choices()),
        ),
    ),
    source="seed 000 §4.3",
    order=10,
    apply=_apply,
    check=_check,
)
