"""Join a sentence's signs by a chosen transition model, or concatenate them with blending.

:func:`retransition` keeps every sign of a synthesized sentence as it is and fills the
frames between one sign's last key and the next one's first with the chosen model
(seed 001 §3.6: the signs are never modified). The search compares the gap's
surroundings at the database's frame rate, so a 60 fps sentence finds transitions
captured at 120 fps. An arm that stays put across a gap (a resting hand) keeps its
frames: a stored transition would set it moving.

:func:`blend_sentence` is seed 004 §4.1's concatenation: each sign made on its own, from
the standard rest position and back (its attack and decay), overlapped and blended
linearly. Every sign starts from the same standard position, which is the root reset of
§3.2.3 for the engine's signs.
"""

import itertools
from dataclasses import replace

import numpy as np

from synthesis.signing.sentence import Sentence, SentenceOptions, parse_glosses, synthesize
from synthesis.signing.signs import SignLibrary
from synthesis.skeleton.retime import sample_curves
from synthesis.transitions.blending import blend_signs
from synthesis.transitions.curves import SIDES, arm_columns
from synthesis.transitions.datadriven import BASELINES, transition
from synthesis.transitions.descriptor import DESCRIPTOR_FRAMES, gap_descriptor

MOVING_DEG = 5.0


def gap_context(
    curves: np.ndarray, end: int, start: int, rate_hz: float, database_rate_hz: float
) -> np.ndarray:
    """Return the descriptor of the gap between frames *end* and *start* at the database's rate."""
    step = 1.0 / database_rate_hz
    before_s = end / rate_hz - step * np.arange(DESCRIPTOR_FRAMES)[::-1]
    after_s = start / rate_hz + step * np.arange(DESCRIPTOR_FRAMES)
    return gap_descriptor(
        sample_curves(curves, rate_hz, before_s), sample_curves(curves, rate_hz, after_s)
    )


def retransition(sentence: Sentence, model: str, search=None, noise=None) -> np.ndarray:
    """Return the sentence's DOFs with every inter-sign gap filled by *model*.

    *model*: ``linear``, ``simple_hermite``, or ``hermite``/``bspline`` with a
    :class:`~synthesis.transitions.search.DescriptorSearch` over a transition database.
    *noise* (n_frames, n_dofs): the liveliness noise in the sentence; the models work
    on the motion without it and it is added back to the frames they fill, so every
    condition breathes alike.
    """
    dofs = np.array(sentence.dofs_rad)
    clean = dofs if noise is None else dofs - noise
    noise = np.zeros_like(dofs) if noise is None else noise
    frames = sentence.token_frames()
    rate = sentence.rate_hz
    for side in SIDES:
        columns = arm_columns(sentence.body.dof_names, side)
        curves = clean[:, columns]
        for (_, end), (start, _) in itertools.pairwise(frames):
            n = start - end - 1
            span = curves[end : start + 1]
            if n < 1 or np.degrees(np.ptp(span, axis=0)).max() < MOVING_DEG:
                continue
            before, after = curves[max(0, end - 8) : end + 1], curves[start : start + 9]
            descriptor = None
            if search is not None and model not in BASELINES:
                database_rate = search.database.entries[0].rate_hz
                descriptor = gap_context(curves, end, start, rate, database_rate)
            filled, _ = transition(model, before, after, n, search, descriptor=descriptor)
            dofs[end + 1 : start, columns] = filled + noise[end + 1 : start, columns]
    return sentence.body.clip(dofs)


# Seed 004 §3.1.3.5: every sign's attack and decay last 1 s, and the overlap is that.
SEED_OVERLAP_MS = 1000.0


def blend_sentence(
    text: str,
    options: SentenceOptions,
    library: SignLibrary | None = None,
    overlap_ms: float | None = None,
) -> tuple[np.ndarray, int]:
    """Return the sentence made sign by sign and blended (seed 004 §4.1), and the overlap.

    Each gloss is synthesized alone, from rest to rest. By default the overlap is the
    shortest decay (last key to the end) or attack (start to the first key), so no blend
    reaches into a sign's keys; the frames of a longer attack or decay then play
    unblended.
    *overlap_ms* fixes it instead, as the seed does (its attack and decay are 1 s,
    :data:`SEED_OVERLAP_MS`); a fixed overlap longer than a sign's attack or decay blends
    into its keys, and one longer than half a sign is refused.
    """
    glosses = parse_glosses(text)
    signs = [
        synthesize(gloss, replace(options, seed=options.seed + k), library)
        for k, gloss in enumerate(glosses)
    ]
    if len(signs) == 1:
        return signs[0].dofs_rad, 0
    if overlap_ms is None:
        attacks = [int(s.token_frames()[0, 0]) for s in signs[1:]]
        decays = [len(s.dofs_rad) - 1 - int(s.token_frames()[-1, 1]) for s in signs[:-1]]
        overlap = min(attacks + decays)
    else:
        overlap = round(overlap_ms * options.rate_hz / 1000)
        short = [g for g, s in zip(glosses, signs, strict=True) if len(s.dofs_rad) < 2 * overlap]
        if short:
            longest_ms = max(len(s.dofs_rad) for s in signs) / options.rate_hz * 1000
            raise ValueError(
                f"A {overlap_ms:g} ms blend overlap needs signs of at least {2 * overlap_ms:g} "
                f"ms (an attack and a decay); {', '.join(short)} is shorter (the built-in "
                f"signs last at most {longest_ms:.0f} ms here). Seed 004's 1 s overlap needs "
                "recordings with 1 s attacks and decays: a lexicon (python -m "
                "synthesis.transitions lexicon --simulate GLOSSES --attack-ms 1000 for "
                "simulated ones)."
            )
    return blend_signs([s.dofs_rad for s in signs], overlap), overlap
