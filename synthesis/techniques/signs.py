"""The sign library a sentence is built from (the story's signs by default)."""

from synthesis.techniques.kinds import SIGNED
from synthesis.techniques.parameters import Parameter
from synthesis.techniques.registry import Technique
from synthesis.techniques.request import Build


def _apply(build: Build) -> Build:
    from dataclasses import replace

    from synthesis.signing.signs import default_library, read_library

    values = build.request.parameters
    library = read_library(values["library"]) if values["library"] else None
    if values["transition_ms"]:
        library = replace(library or default_library(), transition_ms=values["transition_ms"])
    return build.but(library=library) if library is not None else build


TECHNIQUE = Technique(
    name="signs",
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
    ),
    source="spec 03",
    order=20,
    apply=_apply,
)
