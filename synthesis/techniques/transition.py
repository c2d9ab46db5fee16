"""Inter-sign transitions as a technique: keyed, linear, simple Hermite, data-driven, blended.

Seed 001's data-driven transitions and its baselines, and seed 004's concatenation with
linear blending (spec 04). ``keyed`` is the engine's own interpolation of the keys
(monotone cubics), what every sentence had before.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from synthesis.techniques.kinds import SIGNED
from synthesis.techniques.parameters import ClipError, Parameter
from synthesis.techniques.registry import MOTION, Technique

if TYPE_CHECKING:
    from synthesis.techniques.request import Build

TRANSITIONS = ("keyed", "linear", "simple_hermite", "hermite", "bspline", "blended")
LABELS = {
    "keyed": "keyed (the engine's monotone cubics between keys)",
    "linear": "linear (seed 001 baseline)",
    "simple_hermite": "simple Hermite (seed 001 baseline)",
    "hermite": "data-driven Hermite (seed 001)",
    "bspline": "data-driven B-spline (seed 001)",
    "blended": "concatenated with linear blending (seed 004)",
}


def _search(path: str):
    from synthesis.transitions.builtin import database_search
    from synthesis.transitions.database import DatabaseError

    try:
        return database_search(path)
    except DatabaseError as error:
        raise ClipError(str(error)) from None


def _apply(build: Build) -> Build:
    import numpy as np

    values = build.request.parameters
    model = values["transition"]
    if model == "keyed":
        return build
    if model == "blended":
        from synthesis.transitions.lexicon import SignLexicon, blend_recorded
        from synthesis.transitions.sentence import blend_sentence

        fixed = values["blend_overlap_ms"] or None  # 0: the shortest attack or decay
        if isinstance(build.library, SignLexicon):
            from synthesis.transitions.lexicon import LexiconError

            request = build.request
            try:
                dofs, _ = blend_recorded(
                    build.sentence.glosses,
                    build.library,
                    request.rate_hz,
                    request.side,
                    overlap_ms=fixed,
                )
            except LexiconError as error:
                raise ClipError(str(error)) from None
        else:
            try:
                dofs, _ = blend_sentence(
                    build.request.text, build.sentence_options, build.library, overlap_ms=fixed
                )
            except ValueError as error:
                raise ClipError(str(error)) from None
        return build.but(motion=np.asarray(dofs))
    from synthesis.transitions.sentence import retransition

    search = _search(values["transition_db"]) if model in ("hermite", "bspline") else None
    sentence = build.sentence
    return build.but(motion=retransition(sentence, model, search, sentence.liveliness_rad))


def _summary(values) -> str:
    words = LABELS[values["transition"]]
    if values["transition"] in ("hermite", "bspline"):
        words += (
            f", database {values['transition_db']}"
            if values["transition_db"]
            else ", built-in database of simulated captures"
        )
    if values["transition"] == "blended" and values["blend_overlap_ms"]:
        words += f", overlap fixed at {values['blend_overlap_ms']:g} ms"
    return words


TECHNIQUE = Technique(
    name="transition",
    label="Inter-sign transitions",
    kinds=SIGNED,
    parameters=(
        Parameter(
            "transition",
            "choice",
            "keyed",
            "How the arms move from one sign to the next; the signs themselves stay "
            "as they are (except blended, which makes each sign from rest and back "
            "and overlaps them).",
            choices=TRANSITIONS,
            labels=LABELS,
        ),
        Parameter(
            "blend_overlap_ms",
            "float",
            0.0,
            "Blended only: how long each sign's decay overlaps the next one's attack. "
            "0: the shortest attack or decay of the sentence's signs, so no blend reaches "
            "a sign's keys (longer attacks then play partly unblended); 1000: seed 004's "
            "fixed 1 s. Applies to synthesized signs and recorded lexicons alike; a sign or "
            "recording shorter than twice the overlap is refused, by name.",
            minimum=0.0,
            maximum=2000.0,
            units="ms",
        ),
        Parameter(
            "transition_db",
            "file",
            "",
            "A transition database (python -m synthesis.transitions build); empty: "
            "the built-in one, built from simulated captures.",
        ),
    ),
    source="seed 001 ch. 3–5; seed 004 §4.1",
    stage=MOTION,
    order=10,
    apply=_apply,
    summary=_summary,
)
