"""Automated spine and shoulder motion on or off (spec 03; seed 003 §3)."""

from __future__ import annotations

from dataclasses import replace
from typing import TYPE_CHECKING

from synthesis.techniques.kinds import SIGNED
from synthesis.techniques.parameters import Parameter
from synthesis.techniques.registry import Technique

if TYPE_CHECKING:
    from synthesis.techniques.request import Build


def _apply(build: Build) -> Build:
    return build.but(options=replace(build.options, spine=build.request.parameters["spine"]))


TECHNIQUE = Technique(
    name="spine",
    label="Automated spine motion",
    kinds=SIGNED,
    parameters=(
        Parameter(
            "spine",
            "bool",
            True,
            "Seed 003's automated spine bend and twist and "
            "clavicle motion, with staggered onsets; off leaves them out and changes "
            "nothing else that is signed.",
        ),
    ),
    source="seed 003 §3.1–3.3",
    order=30,
    apply=_apply,
)
