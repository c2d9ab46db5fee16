"""The sign library a sentence is built from (the story's signs by default)."""

from __future__ import annotations

from typing import TYPE_CHECKING

from synthesis.techniques.kinds import SIGNED
from synthesis.techniques.parameters import ClipError, Parameter
from synthesis.techniques.registry import Technique

if TYPE_CHECKING:
    from synthesis.techniques.request import Build


def _check(values) -> None:
    if values["lexicon"] and values["library"]:
        raise ClipError("Set a sign library or a lexicon of recorded signs, not both.")
    if values["lexicon"] and (not values["spine"] or values["face"] != "on"):
        raise ClipError(
            "Recorded signs carry their signer's own spine and face: spine off and the "
            "face settings apply to the library's key-posture signs only."
        )


def _apply(build: Build) -> Build:
    from dataclasses import replace

    from synthesis.signing.signs import default_library, read_library

    values = build.request.parameters
    if values["lexicon"]:
        from synthesis.transitions.lexicon import LexiconError, read_lexicon

        try:
            return build.but(library=read_lexicon(values["lexicon"]))
        except LexiconError as error:
            raise ClipError(str(error)) from None
    library = read_library(values["library"]) if values["library"] else None
    if values["transition_ms"]:
        library = replace(library or default_library(), transition_ms=values["transition_ms"])
    return build.but(library=library) if library is not None else build


TECHNIQUE = Technique(
    name="signs",
    chooses_content=True,
    label="Sign library",
    kinds=SIGNED,
    parameters=(
        Parameter(
            "library",
            "file",
            "",
            "A sign library (YAML) to use instead of the one shipped (synthesis/data/signs.yaml).",
        ),
        Parameter(
            "transition_ms",
            "float",
            0.0,
            "How long each transition between signs lasts; 0: the library's own. "
            "Seed 001's captured transitions lasted 540 ms on average.",
            minimum=0,
            maximum=3000,
            units="ms",
        ),
        Parameter(
            "lexicon",
            "file",
            "",
            "A lexicon of recorded signs (python -m synthesis.transitions lexicon): every "
            "gloss is played as recorded, joined by the transition technique. Liveliness "
            "noise is not added to recordings.",
        ),
    ),
    source="spec 03",
    order=20,
    apply=_apply,
    check=_check,
)
