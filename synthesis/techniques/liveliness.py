"""Liveliness: coherent band-limited noise on every joint, so a still signer breathes."""

from __future__ import annotations

from dataclasses import replace
from typing import TYPE_CHECKING

from synthesis.techniques.kinds import SIGNED
from synthesis.techniques.parameters import Parameter
from synthesis.techniques.registry import Technique

if TYPE_CHECKING:
    from synthesis.techniques.request import Build


def _apply(build: Build) -> Build:
    from synthesis.signing.liveliness import Liveliness

    liveliness = Liveliness() if build.request.parameters["liveliness"] else None
    return build.but(options=replace(build.sentence_options, liveliness=liveliness))


TECHNIQUE = Technique(
    name="liveliness",
    label="Liveliness noise",
    kinds=SIGNED,
    parameters=(
        Parameter(
            "liveliness",
            "bool",
            True,
            "Small, slow noise on every joint (smaller and "
            "faster distally, larger on the weak side), seeded per item.",
        ),
    ),
    source="spec 03 (clip hygiene)",
    order=40,
    apply=_apply,
)
