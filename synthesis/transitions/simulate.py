"""Simulated sentence captures with known segments, to build and test a transition database.

Labelled simulated everywhere: these are the engine's own sentences at 120 fps (the
seed's capture rate), whose transitions are replaced by a model of a human arm's
transition, not recordings of people. Between two signs each arm curve runs along a
minimum-jerk profile (Flash and Hogan's reach) with the sentence's liveliness noise on
top. Each simulated signer has their own way of moving, as the seed's four interpreters
had (seed 001 §3.1, §5.1: 63.6 % of best matches came from the query's own interpreter,
only 12.5 % were the same transition by another), and it changes the curves' shape, not
only their size:

- *bulge*: each curve's mid-transition excursion per radian the shoulder and elbow
  travel (the elbow lifts to clear the body), its sign the signer's own for the
  forearm and wrist;
- *lag*: each curve's timing against the others (one signer's elbow leads the
  shoulder, another's trails it), which moves and skews its velocity peak;
- *wave*: an S-shaped excursion (overshoot then correction) per radian travelled;
- *posture*: where the signer's arm passes mid-transition whatever the signs (how they
  hold the arm between signs), in radians;
- *stance*: how the signer holds the arm throughout, signs included (an offset per
  curve, radians), so that a signer's signs, and the transitions' ends, are their own.

Transitions last 0.3–0.9 s, 0.54 s on average as in the seed's captures (§4.2).
Signers sign a shared set of sentences and some of their own.
"""

import itertools
from dataclasses import dataclass

import numpy as np

from synthesis.signing.sentence import SentenceOptions, synthesize
from synthesis.signing.signs import SignLibrary, default_library
from synthesis.skeleton.retime import minimum_jerk
from synthesis.transitions.curves import SIDES, arm_columns
from synthesis.transitions.recording import SegmentedRecording
from synthesis.transitions.segments import Segment, Segmentation

CAPTURE_RATE_HZ = 120.0
MEAN_TRANSITION_MS = 540.0
ZERO7 = (0.0,) * 7


@dataclass(frozen=True)
class SignerStyle:
    """How a simulated signer moves between signs (the module's docstring says each part).

    *bulge*, *wave* (7,): per radian travelled; *lag* (7,): share of the transition,
    within ±0.6 so each curve still moves one way; *posture* (7,) rad; *skew*: the
    exponent on normalized time (below 1 peaks early); *jitter*: the spread (share) of
    each transition's bulge, wave and lag around the habit.
    """

    name: str
    bulge: tuple[float, ...]
    skew: float
    jitter: float = 0.3
    lag: tuple[float, ...] = ZERO7
    wave: tuple[float, ...] = ZERO7
    posture: tuple[float, ...] = ZERO7
    stance: tuple[float, ...] = ZERO7


def signer_styles(count: int, rng: np.random.Generator) -> tuple[SignerStyle, ...]:
    """Return *count* simulated signers with their own habits (*rng* draws them)."""
    base = np.array([0.10, 0.30, -0.10, 0.25, 0.05, 0.05, 0.0])
    styles = []
    for k in range(count):
        signs = np.where(np.arange(7) >= 4, rng.choice([-1.0, 1.0], 7), 1.0)
        bulge = base * rng.uniform(0.3, 1.7, 7) * signs + np.where(
            np.arange(7) == 6, rng.normal(0.0, 0.05), 0.0
        )
        styles.append(
            SignerStyle(
                f"sim{k + 1}",
                tuple(np.round(bulge, 4)),
                float(np.round(rng.uniform(0.75, 1.05), 3)),
                lag=tuple(np.round(rng.uniform(-0.5, 0.5, 7), 3)),
                wave=tuple(np.round(rng.normal(0.0, 0.08, 7), 4)),
                posture=tuple(np.round(rng.normal(0.0, 0.06, 7), 4)),
                stance=tuple(np.round(rng.normal(0.0, 0.08, 7), 4)),
            )
        )
    return tuple(styles)


def human_transition(
    v0: np.ndarray, v1: np.ndarray, n_frames: int, style: SignerStyle, rng: np.random.Generator
) -> np.ndarray:
    """Return a simulated arm's *n_frames* between poses *v0* and *v1* (7,), (n, 7) rad."""
    v0, v1 = np.asarray(v0, float), np.asarray(v1, float)
    s = (np.arange(1, n_frames + 1) / (n_frames + 1))[:, None]
    spread = 1 + style.jitter * rng.standard_normal((3, 7))
    lag = np.clip(np.asarray(style.lag) * spread[0], -0.6, 0.6)
    # s + lag·sin(πs)/π keeps the ends and stays increasing for |lag| < 1.
    timed = np.clip(s + lag * np.sin(np.pi * s) / np.pi, 0.0, 1.0)
    shaped = minimum_jerk(timed ** (style.skew * rng.uniform(0.95, 1.05)))
    travel = np.linalg.norm((v1 - v0)[:4])
    bulge = np.asarray(style.bulge) * travel * spread[1]
    wave = np.asarray(style.wave) * travel * spread[2]
    posture = np.asarray(style.posture)
    return (
        v0
        + shaped * (v1 - v0)
        + np.sin(np.pi * s) ** 2 * (bulge + posture)
        + np.sin(2 * np.pi * s) * np.sin(np.pi * s) * wave
    )


def simulate_capture(
    glosses: tuple[str, ...],
    style: SignerStyle,
    rng: np.random.Generator,
    name: str,
    library: SignLibrary | None = None,
    rate_hz: float = CAPTURE_RATE_HZ,
) -> SegmentedRecording:
    """Return a simulated capture of *glosses* by *style*, segmented, labelled simulated."""
    library = library or default_library()
    gaps_ms = tuple(
        np.clip(rng.lognormal(np.log(MEAN_TRANSITION_MS), 0.3, len(glosses) - 1), 300, 900).round()
    )
    seed = int(rng.integers(2**31))
    options = SentenceOptions(rate_hz=rate_hz, seed=seed, gaps_ms=gaps_ms)
    sentence = synthesize(" ".join(glosses), options, library)
    dofs, noise = np.array(sentence.dofs_rad), sentence.liveliness_rad
    clean = dofs - noise
    frames = sentence.token_frames()
    for side in SIDES:
        columns = arm_columns(sentence.body.dof_names, side)
        clean[:, columns] += np.asarray(style.stance)
        dofs[:, columns] += np.asarray(style.stance)
        for (_, end), (start, _) in itertools.pairwise(frames):
            inside = slice(end + 1, start)
            path = human_transition(
                clean[end, columns], clean[start, columns], start - end - 1, style, rng
            )
            dofs[inside, columns] = path + noise[inside, columns]
    return SegmentedRecording(
        name,
        dofs,
        tuple(sentence.body.dof_names),
        rate_hz,
        _segmentation(name, glosses, frames, len(dofs)),
        style.name,
        simulated=True,
    )


def _segmentation(name: str, glosses, frames: np.ndarray, n_frames: int) -> Segmentation:
    """Return rest, sign, transition, sign, …, rest over a sentence's token frames."""
    segments = [Segment("rest", 1, 0, int(frames[0, 0]) - 1, "approach")]
    for k, (gloss, (start, end)) in enumerate(zip(glosses, frames, strict=True)):
        if k:
            segments.append(
                Segment(
                    "transition",
                    len(segments) + 1,
                    int(frames[k - 1, 1]) + 1,
                    int(start) - 1,
                    f"TRANSITION{k}",
                )
            )
        segments.append(Segment("sign", len(segments) + 1, int(start), int(end), gloss))
    segments.append(
        Segment("rest", len(segments) + 1, int(frames[-1, 1]) + 1, n_frames - 1, "return")
    )
    return Segmentation(name, tuple(segments))


def simulated_captures(
    signers: int = 4,
    sentences: int = 6,
    seed: int = 0,
    library: SignLibrary | None = None,
    rate_hz: float = CAPTURE_RATE_HZ,
    shared: float = 0.5,
) -> list[SegmentedRecording]:
    """Return *sentences* simulated captures by each of *signers* simulated signers.

    A *shared* share of the sentences (random glosses of the library, 4–6 signs) is
    signed by every signer, as the seed's interpreters signed the same sentences; the
    rest are each signer's own. *seed* fixes everything.
    """
    if not 0 <= shared <= 1:
        raise ValueError(f"shared is a share of the sentences (0 to 1), not {shared}.")
    library = library or default_library()
    rng = np.random.default_rng(seed)
    glosses = sorted(library.signs)

    def text() -> tuple[str, ...]:
        return tuple(str(g) for g in rng.choice(glosses, int(rng.integers(4, 7)), replace=False))

    common = [text() for _ in range(round(shared * sentences))]
    styles = signer_styles(signers, rng)
    texts = {
        style.name: common + [text() for _ in range(sentences - len(common))] for style in styles
    }
    return [
        simulate_capture(words, style, rng, f"{style.name}s{k + 1:02d}", library, rate_hz)
        for style in styles
        for k, words in enumerate(texts[style.name])
    ]
