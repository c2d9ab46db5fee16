"""The sign library a sentence is built from (the story's signs by default)."""

from synthesis.techniques.parameters import Parameter
from synthesis.techniques.registry import Technique
from synthesis.techniques.request import Build


def _apply(build: Build) -> Build:
    from synthesis.signing.signs import read_library

    path = build.request.parameters["library"]
    return build.but(library=read_library(path)) if path else build


TECHNIQUE = Technique(
    name="signs",
    label="Sign library",
    kinds=frozenset({"sentence"}),
    parameters=(
        Parameter(
            "library",
            "file",
            "",
            "A sign library (YAML) to use instead of the one shipped (synthesis/data/signs.yaml).",
        ),
    ),
    source="spec 03",
    order=20,
    apply=_apply,
)
