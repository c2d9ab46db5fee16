"""The face on, neutral or off: non-manual signals as a technique (issue 16; seed 003 §4)."""

from __future__ import annotations

from dataclasses import replace
from typing import TYPE_CHECKING

from synthesis.techniques.kinds import SIGNED
from synthesis.techniques.parameters import Parameter
from synthesis.techniques.registry import Technique

if TYPE_CHECKING:
    from synthesis.techniques.request import Build


def _apply(build: Build) -> Build:
    return build.but(options=replace(build.sentence_options, face=build.request.parameters["face"]))


TECHNIQUE = Technique(
    name="face",
    label="Face",
    kinds=SIGNED,
    parameters=(
        Parameter(
            "face",
            "choice",
            "on",
            "on: the sentence's non-manual signals (brows, eyes, mouth, head shakes and "
            "nods over the glosses they mark), blinks at phrase boundaries and gaze leading "
            "the head; neutral: blinks and gaze only, an expressionless face; off: a still "
            "face. Changes only the face's channels and the head's non-manual movements.",
            choices=("on", "neutral", "off"),
            labels={"on": "non-manual signals", "neutral": "neutral face", "off": "still face"},
        ),
    ),
    source="seed 003 §4; issue 16",
    order=35,
    apply=_apply,
)
