"""Synthesize a signed sentence on the upper body, with automated spine motion on or off.

A sentence is a gloss sequence (``"BUT SURPRISE MY BROTHER GET NEW C-A-R"``); glosses
come from a sign library (synthesis.signing.signs), letter-hyphen-letter words are fingerspelled.
Each key posture becomes body DOFs (seed 003 §3):

- **Spine on**: the automated spine and clavicle motion (synthesis.signing.spine), computed from
  the hand targets, is added on top of the keyed spine; then the arms reach the targets
  by analytic IK (synthesis.rigs.ik) from the torso as it now stands, so the hands are where
  the sign puts them; and the spine and clavicles start earlier than the arm.
- **Spine off**: no automated motion; the arms reach the same targets from the keyed
  torso. Keys, handshapes, head, the head and neck's stagger and the noise are the same,
  so the versions differ in the spine, the clavicles and the arm angles that make up
  for them, not in where the hands go (spec 03).

The body's onsets are staggered: gaze (the eyes, which turn with a keyed head turn)
→ head → neck → hips and spine, lower to upper → clavicle → arm. Keys are joined by
monotone cubics (PCHIP, C¹, eased into and out of held postures). The face's channels
come from the text's and the signs' non-manual signals and the blinks at phrase
boundaries (synthesis.signing.nonmanual), as the face option says; liveliness noise
(synthesis.signing.liveliness) is added last, the same in all conditions for a given
seed.
"""

import re
from dataclasses import dataclass, field

import numpy as np
from scipy.interpolate import PchipInterpolator

from synthesis.fingerspelling.alphabet import AlphabetError
from synthesis.rigs.body import BodyModel
from synthesis.rigs.face import is_face_dof
from synthesis.signing.keys import SPINE_JOINTS, Key, KeySolver
from synthesis.signing.liveliness import Liveliness, joint_group
from synthesis.signing.nonmanual import (
    NonmanualError,
    Span,
    Track,
    blink_channels,
    nonmanual_channels,
    parse_spans,
)
from synthesis.signing.signs import SignError, SignLibrary, default_library
from synthesis.signing.spine import SpineParams

REST_HOLD_MS = 150.0
LEAD_MS = 450.0
# A phrase-boundary blink starts this long after the phrase's last sign.
BLINK_AFTER_MS = 60.0
FACE_MODES = ("on", "neutral", "off")


@dataclass(frozen=True)
class Stagger:
    """Onset offsets (ms; negative starts earlier than the key) per joint group.

    Seed 003 §3.5: gaze → neck → spine/hips → clavicle → arm, one to two frames apart
    at 30 fps (50 ms here), tighter within the spine (hips lead the upper spine). The
    eyes lead the head they turn with.
    """

    head_ms: float = -200.0
    neck_ms: float = -175.0
    spine_ms: tuple[float, float, float] = (-135.0, -120.0, -105.0)  # lower, middle, upper
    clavicle_ms: float = -50.0
    eyes_ms: float = -250.0


@dataclass(frozen=True)
class SentenceOptions:
    """How to synthesize: spine condition, face, tuning, frame rate, noise seed.

    *face*: ``on`` (non-manual signals, blinks, gaze), ``neutral`` (blinks and gaze, no
    non-manual signals) or ``off`` (a still face: every face channel at rest).
    """

    spine: bool = True
    face: str = "on"
    params: SpineParams = field(default_factory=SpineParams)
    stagger: Stagger = field(default_factory=Stagger)
    liveliness: Liveliness | None = field(default_factory=Liveliness)
    rate_hz: float = 60.0
    seed: int = 0
    dominant: str = "right"
    gaps_ms: tuple[float, ...] | None = None


@dataclass(frozen=True)
class Sentence:
    """A synthesized sentence: body DOFs per frame and what produced them.

    *dofs_rad* (n_frames, n_dofs); *automated_rad* the automated spine and clavicle part
    (zero with the spine off); *key_times_s* (n_keys,); *glosses* the parsed tokens;
    *tracks* the non-manual signals placed in time and *blinks_ms* the blinks' starts;
    *tokens_s* (n_tokens, 2) each token's first and last key (between one token's last
    key and the next one's first lies the transition); *liveliness_rad* (n_frames,
    n_dofs) what the liveliness noise added (zeros without), so a later step can work on
    the motion without it and put it back.
    """

    body: BodyModel
    dofs_rad: np.ndarray
    automated_rad: np.ndarray
    rate_hz: float
    key_times_s: np.ndarray
    glosses: tuple[str, ...]
    tracks: tuple[Track, ...] = ()
    blinks_ms: tuple[float, ...] = ()
    tokens_s: np.ndarray = field(default_factory=lambda: np.zeros((0, 2)))
    liveliness_rad: np.ndarray | None = None

    @property
    def duration_s(self) -> float:
        return (len(self.dofs_rad) - 1) / self.rate_hz

    def token_frames(self) -> np.ndarray:
        """Return each token's first and last frame (n_tokens, 2): the frames nearest its
        first and last key."""
        return np.rint(np.asarray(self.tokens_s) * self.rate_hz).astype(int)


def parse_glosses(text: str) -> tuple[str, ...]:
    """Return a sentence's tokens: glosses and fingerspelled words (``T-O-Y``), without
    the non-manual spans the text marks."""
    try:
        text = parse_spans(text)[0]
    except NonmanualError as error:
        raise SignError(str(error)) from None
    tokens = []
    for word in re.split(r"\s+", text.strip()):
        word = word.strip(',.!?;:—–"').upper()
        if word and word not in ("-", "—", "–"):
            tokens.append(word)
    if not tokens:
        raise SignError("Nothing to sign: the sentence is empty.")
    return tuple(tokens)


def _is_spelled(token: str) -> bool:
    parts = token.split("-")
    return len(parts) > 1 and all(len(p) == 1 and p.isalpha() for p in parts)


def _spelled_keys(token: str, library: SignLibrary, rest: dict, t: float) -> list[Key]:
    """Return a fingerspelled token's keys from *t* (ms): each letter held, then moved on."""
    spelling = library.spelling
    keys: list[Key] = []
    for character in token.split("-"):
        hand = library.hand("right", {**spelling, "shape": character}, token)
        pose = {"right": hand, "left": rest["left"]}
        keys += [Key(t, pose, {}, {}), Key(t + float(spelling.get("hold_ms", 110)), pose, {}, {})]
        t = keys[-1].ms + float(spelling.get("transition_ms", 110))
    return keys


def _sign_keys(sign, rest: dict, t: float) -> list[Key]:
    """Return a sign's keys from *t* (ms); a hand the sign leaves out stays at rest, and a
    hand holds its last pose between the keys that name it."""
    used = {side for key in sign for side in key.hands}
    last = {side: next(k.hands[side] for k in sign if side in k.hands) for side in used}
    keys = []
    for key in sign:
        last.update(key.hands)
        hands = {side: last[side] if side in used else rest[side] for side in rest}
        keys.append(Key(t + key.ms, hands, key.spine_deg, key.head_deg))
        if key.hold_ms > 0:
            keys.append(Key(t + key.ms + key.hold_ms, hands, key.spine_deg, key.head_deg))
    return keys


def timeline(
    glosses, library: SignLibrary, gaps_ms=None
) -> tuple[list[Key], list[tuple[float, float]]]:
    """Return the sentence's keys in time order, holds written out as repeated keys, and
    each token's first and last key (ms).

    *gaps_ms* gives each transition between tokens its own length (the library's
    ``transition_ms`` by default).
    """
    if gaps_ms is not None and len(gaps_ms) != len(glosses) - 1:
        raise SignError(
            f"{len(glosses)} signs have {len(glosses) - 1} transitions, not {len(gaps_ms)}."
        )
    gaps = list(gaps_ms) if gaps_ms is not None else [library.transition_ms] * (len(glosses) - 1)
    rest = {side: library.hand(side, library.rest, "rest") for side in ("right", "left")}
    keys = [Key(0.0, dict(rest), {}, {}), Key(REST_HOLD_MS, dict(rest), {}, {})]
    t = LEAD_MS
    tokens_ms = []
    for token in glosses:
        first = len(keys)
        if _is_spelled(token):
            keys += _spelled_keys(token, library, rest, t)
        else:
            keys += _sign_keys(library.sign(token), rest, t)
        tokens_ms.append((keys[first].ms, keys[-1].ms))
        t = keys[-1].ms + (
            gaps[len(tokens_ms) - 1] if len(tokens_ms) <= len(gaps) else library.transition_ms
        )
    keys += [Key(t, dict(rest), {}, {}), Key(t + REST_HOLD_MS, dict(rest), {}, {})]
    return keys, tokens_ms


def _offsets_ms(names: list[str], stagger: Stagger) -> np.ndarray:
    """Return each DOF's onset offset (ms): the arms and hands keep the keys' times."""
    offsets = np.zeros(len(names))
    for i, name in enumerate(names):
        group = joint_group(name)
        if group == "eyes":
            offsets[i] = stagger.eyes_ms
        elif group == "head":
            offsets[i] = stagger.head_ms
        elif group == "neck":
            offsets[i] = stagger.neck_ms
        elif group == "spine":
            joint = next(j for j in SPINE_JOINTS if name.startswith(j))
            offsets[i] = stagger.spine_ms[SPINE_JOINTS.index(joint)]
        elif group == "clavicle":
            offsets[i] = stagger.clavicle_ms
    return offsets


def _interpolate(times_s, values, offsets_ms, at_s) -> np.ndarray:
    """Return values (n_frames, n_dofs): each DOF's keys shifted by its offset, PCHIP."""
    out = np.empty((len(at_s), values.shape[1]))
    for offset in np.unique(offsets_ms):
        columns = offsets_ms == offset
        shifted = times_s + offset / 1000.0
        curve = PchipInterpolator(shifted, values[:, columns], axis=0, extrapolate=False)
        sampled = curve(np.clip(at_s, shifted[0], shifted[-1]))
        out[:, columns] = sampled
    return out


def synthesize(
    text: str, options: SentenceOptions | None = None, library: SignLibrary | None = None
) -> Sentence:
    """Return the sentence *text* synthesized on the upper body (spec 03).

    *text* may mark non-manual signals over spans of glosses (``I LOST [rhq WHERE]``;
    synthesis.signing.nonmanual).
    """
    options = options or SentenceOptions()
    library = library or default_library()
    if options.face not in FACE_MODES:
        raise SignError(f"face must be one of {', '.join(FACE_MODES)}, not {options.face!r}.")
    try:
        plain, spans, boundaries = parse_spans(text)
    except NonmanualError as error:
        raise SignError(str(error)) from None
    glosses = parse_glosses(plain)
    try:
        keys, tokens_ms = timeline(glosses, library, options.gaps_ms)
    except AlphabetError as error:
        raise SignError(str(error)) from None
    body = BodyModel(options.dominant)
    names = body.dof_names
    # Signs are written for a right-handed signer; a left-handed one mirrors them.
    solver = KeySolver(BodyModel("right"), options.params)
    auto_keys = solver.automated(keys) if options.spine else np.zeros((len(keys), len(names)))
    times_s = np.array([k.ms for k in keys]) / 1000.0
    count = int(np.floor(times_s[-1] * options.rate_hz + 1e-9)) + 1
    at_s = np.arange(count) / options.rate_hz
    offsets = _offsets_ms(names, options.stagger)
    # The arms reach the key's targets from the torso as the spine, leading by the
    # stagger, has left it at the key's time, so the hands' positions are the same in
    # both conditions (and a hand placed on the body keeps its contact).
    keyed = solver.keys(
        keys, auto_keys, lambda key_dofs: _interpolate(times_s, key_dofs, offsets, times_s)
    )
    dofs = _interpolate(times_s, keyed, offsets, at_s)
    automated = _interpolate(times_s, auto_keys, offsets, at_s)
    # Checked whatever the face shows: a misspelt signal is an error in every condition.
    tracks = _tracks(glosses, spans, tokens_ms, library)
    if options.face != "on":
        tracks = ()
    blinks = tuple(tokens_ms[i][1] + BLINK_AFTER_MS for i in sorted(boundaries))
    if options.face == "off":
        blinks = ()
        dofs[:, [is_face_dof(name) for name in names]] = 0.0
    dofs = dofs + nonmanual_channels(names, library.nonmanuals, tracks, at_s)
    dofs = dofs + blink_channels(names, blinks, at_s)
    if options.dominant == "left":
        dofs, automated = body.mirror_pose(dofs), body.mirror_pose(automated)
    quiet = body.clip(dofs)
    if options.liveliness is not None:
        rng = np.random.default_rng(options.seed)
        dofs = dofs + options.liveliness.sample(body, count, options.rate_hz, rng)
    lively = body.clip(dofs)
    return Sentence(
        body,
        lively,
        automated,
        options.rate_hz,
        times_s,
        glosses,
        tracks,
        blinks,
        np.array(tokens_ms).reshape(-1, 2) / 1000.0,
        lively - quiet,
    )


def _tracks(glosses, spans, tokens_ms, library: SignLibrary) -> tuple[Track, ...]:
    """Return the non-manual signals of the text's spans and of its signs, in time."""
    marked = list(spans)
    for k, token in enumerate(glosses):
        marked += [Span(name, k, k) for name in library.sign_nonmanuals.get(token, ())]
    tracks = []
    for span in marked:
        if span.marker not in library.nonmanuals:
            known = ", ".join(sorted(library.nonmanuals))
            raise SignError(f"Unknown non-manual signal {span.marker!r} (known: {known}).")
        tracks.append(
            Track(span.marker, tokens_ms[span.first][0], tokens_ms[span.last][1], span.intensity)
        )
    return tuple(sorted(tracks, key=lambda track: (track.start_ms, track.marker)))
