"""The item kinds the engine renders: fingerspelled words, signed sentences and sign pairs.

Each kind starts a clip's build from its request and, once the prepare-stage techniques
have chosen a performance, a timing or synthesis options, makes the motion.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import TYPE_CHECKING, Any

import numpy as np

from synthesis.techniques.parameters import ClipError
from synthesis.techniques.registry import ItemKind

if TYPE_CHECKING:
    from synthesis.techniques.request import Build


def _check_word(text: str, values: Mapping[str, Any]) -> None:
    from synthesis.fingerspelling.spelling import word_letters

    try:
        word_letters(text, values["alphabet"])
    except ValueError as error:
        raise ClipError(str(error)) from None


def _start_word(build: Build) -> Build:
    _check_word(build.request.text, build.request.parameters)
    return build


def _finish_word(build: Build) -> Build:
    """Spell the word with the chosen timing, or retime the chosen performance onto it.

    Seed 000 §4.3: with a performance, every condition is that performance, its holds and
    transitions moved onto the condition's timing; the Motion capture condition plays it
    as performed.
    """
    from synthesis.fingerspelling.spelling import spell
    from synthesis.rigs.hand import HandModel

    request = build.request
    if build.performance is None:
        from synthesis.rigs.posture import hand_motion_on

        alphabet = request.parameters["alphabet"]
        hand = spell(request.text, request.side, request.rate_hz, build.timing, alphabet=alphabet)
        return build.but(motion=hand_motion_on(build.rig, request.side, hand))
    from synthesis.rigs.retarget import retarget
    from synthesis.skeleton.retime import resample
    from synthesis.timing.recordings import retime

    if not isinstance(build.rig, HandModel):
        raise ClipError(
            "A recorded or simulated performance renders in the hand view for now: "
            "set view to 'hand' (--view hand)."
        )
    timing, performance = build.timing, build.performance
    if timing is None or timing is performance.extraction.timing:
        motion = performance.motion  # as performed
    else:
        motion = retime(performance, timing)
    if abs(motion.rate_hz - request.rate_hz) > 1e-9:
        motion = resample(motion, request.rate_hz)
    return build.but(motion=retarget(motion, build.rig))


def _start_sentence(build: Build) -> Build:
    from synthesis.signing.sentence import SentenceOptions

    request = build.request
    options = SentenceOptions(rate_hz=request.rate_hz, seed=request.seed, dominant=request.side)
    return build.but(options=options)


def _check_sign_pair(text: str, values: Mapping[str, Any]) -> None:
    """Refuse anything but two glosses: the transition between them is the point."""
    from synthesis.signing.sentence import parse_glosses
    from synthesis.signing.signs import SignError

    try:
        glosses = parse_glosses(text)
    except SignError as error:
        raise ClipError(str(error)) from None
    if len(glosses) != 2:
        raise ClipError(
            f"A sign pair is two glosses (the transition between them is what is studied), "
            f"not {len(glosses)}: {' '.join(glosses)}."
        )


def _start_sign_pair(build: Build) -> Build:
    _check_sign_pair(build.request.text, build.request.parameters)
    return _start_sentence(build)


def _finish_sentence(build: Build) -> Build:
    from synthesis.signing.sentence import parse_glosses, synthesize
    from synthesis.signing.signs import SignError
    from synthesis.transitions.lexicon import GAP_MS, LexiconError, SignLexicon, assemble

    if isinstance(build.library, SignLexicon):
        request = build.request
        gap_ms = request.parameters["transition_ms"] or GAP_MS
        try:
            glosses = parse_glosses(request.text)
            sentence = assemble(glosses, build.library, request.rate_hz, gap_ms, request.side)
        except (LexiconError, SignError) as error:
            raise ClipError(str(error)) from None
        return build.but(motion=np.asarray(sentence.dofs_rad), result=sentence)
    sentence = synthesize(build.request.text, build.options, build.library)
    return build.but(motion=np.asarray(sentence.dofs_rad), result=sentence)


WORD = ItemKind(
    "word", "fingerspelled word", ("hand", "upper-body"), _start_word, _finish_word, _check_word
)
SENTENCE = ItemKind("sentence", "sentence", ("upper-body",), _start_sentence, _finish_sentence)
SIGN_PAIR = ItemKind(
    "sign_pair", "sign pair", ("upper-body",), _start_sign_pair, _finish_sentence, _check_sign_pair
)
# The kinds made of signs: every sentence technique applies to them all.
SIGNED = frozenset({SENTENCE.name, SIGN_PAIR.name})
