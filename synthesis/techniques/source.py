"""Where a fingerspelled word's motion comes from: the engine's alphabet, a simulated
capture, or a recording (seed 000 §4.3: conditions retime one performance).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from synthesis.techniques.parameters import ClipError, Parameter
from synthesis.techniques.registry import Technique

if TYPE_CHECKING:
    from synthesis.techniques.request import Build

SOURCES = ("alphabet", "simulated", "recording")


def _check(values) -> None:
    if values["source"] == "recording" and not values["recording"]:
        raise ClipError(
            "source 'recording' needs the recording: set recording to a BVH or .pose file of "
            "the word (--recording FILE.bvh)."
        )
    if values["recording"] and values["source"] != "recording":
        raise ClipError(f"recording is set but source is {values['source']!r}: set source "
                        "to 'recording' or leave recording empty.")  # fmt: skip


def _apply(build: Build) -> Build:
    from synthesis.techniques.timing import variable_model
    from synthesis.timing.recordings import Recording

    request, values = build.request, build.request.parameters
    if values["source"] == "simulated":
        # One performance per item, shared by its conditions: only the timing differs.
        performance = Recording.simulate(request.text, request.seed, variable_model(values),
                                         request.side, request.rate_hz)  # fmt: skip
        return build.but(performance=performance)
    if values["source"] == "recording":
        return build.but(performance=Recording.read(values["recording"], request.text,
                                                    request.side))  # fmt: skip
    return build


TECHNIQUE = Technique(
    name="source",
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
    ),
    source="seed 000 §4.3",
    order=10,
    apply=_apply,
    check=_check,
)
