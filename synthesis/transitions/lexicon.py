"""A sign lexicon of recordings: sentences assembled from recorded sign clips.

A lexicon is a manifest (:data:`FORMAT`, versioned JSON) naming each gloss's recording —
a BVH of the engine's body or a captured ``.pose`` file, relative to the manifest — with
its SHA-256, so a clip's hash changes when a recording does. A recording's segmentation
beside it (``NAME.segments.json``/``.xml``) marks its sign; what comes before is the
attack from rest and what follows the decay back to it (seed 004 §3.1.3). Without one,
the whole clip is the sign. Recordings are read as the transition recordings are
(:func:`~synthesis.transitions.recording.read_body_dofs`), their root reset to the
standard position (seed 004 §3.2.3).

:func:`assemble` plays the signs as recorded, one after the other, joined by an eased
move of every DOF over the gap (which a transition technique then replaces for the
arms); :func:`blend_recorded` is seed 004's concatenation of the whole clips.
"""

import hashlib
import json
import os
from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np

from synthesis.formats import check_header
from synthesis.rigs.body import BodyModel
from synthesis.signing.sentence import Sentence
from synthesis.skeleton.retime import resample_curves
from synthesis.transitions.blending import blend_signs
from synthesis.transitions.recording import (
    RecordingError,
    SegmentedRecording,
    read_body_dofs,
    read_segmentation,
    segmentation_file,
    write_recording,
)
from synthesis.transitions.segments import SegmentationError

FORMAT = "signstudy.sign-lexicon"
FORMAT_VERSION = 1
GAP_MS = 300.0


class LexiconError(ValueError):
    """A lexicon that cannot be read, or a gloss it does not hold."""


@dataclass(frozen=True, eq=False)
class RecordedSign:
    """One recorded sign: the body's DOFs over the clip and where the sign lies in it.

    *dofs_rad* (n_frames, n_dofs) at *rate_hz*; *sign_frames* the sign's first and last
    frame (before them the attack, after them the decay).
    """

    gloss: str
    dofs_rad: np.ndarray
    rate_hz: float
    sign_frames: tuple[int, int]
    simulated: bool = False

    @property
    def sign(self) -> np.ndarray:
        """Return the sign's own frames, without attack and decay."""
        first, last = self.sign_frames
        return self.dofs_rad[first : last + 1]

    def resampled(self, rate_hz: float) -> "RecordedSign":
        """Return the sign at *rate_hz* (linear between frames, marks moved to the nearest)."""
        if abs(rate_hz - self.rate_hz) < 1e-9:
            return self
        dofs = resample_curves(self.dofs_rad, self.rate_hz, rate_hz)
        first, last = (round(f / self.rate_hz * rate_hz) for f in self.sign_frames)
        return replace(
            self, dofs_rad=dofs, rate_hz=rate_hz, sign_frames=(first, min(last, len(dofs) - 1))
        )


@dataclass(frozen=True, eq=False)
class SignLexicon:
    """Recorded signs by gloss, read from the manifest at *source*."""

    signs: dict[str, RecordedSign]
    source: str = ""

    @property
    def simulated(self) -> bool:
        """Return whether any sign is a simulated recording."""
        return any(sign.simulated for sign in self.signs.values())

    def sign(self, gloss: str) -> RecordedSign:
        """Return the recording of *gloss*; raise :class:`LexiconError` naming what is held."""
        try:
            return self.signs[gloss]
        except KeyError:
            raise LexiconError(
                f"The lexicon {self.source} has no recording of {gloss!r}; it holds "
                f"{', '.join(sorted(self.signs))}."
            ) from None


def _sha256(path: Path) -> str:
    return hashlib.sha256(path.read_bytes()).hexdigest()


def read_sign(path: str | Path, gloss: str | None = None, simulated: bool = False) -> RecordedSign:
    """Return the recorded sign at *path* (its gloss the file's name unless given).

    Its segmentation beside it marks the sign (one ``sign`` segment); without one, the
    whole clip is the sign.
    """
    path = Path(path)
    gloss = gloss or path.name.split(".")[0].upper()
    try:
        dofs, _, rate_hz = read_body_dofs(path)
        beside = segmentation_file(path)
        segments = read_segmentation(beside)[0].segments if beside else ()
    except (RecordingError, SegmentationError) as error:
        raise LexiconError(str(error)) from None
    signs = [s for s in segments if s.kind == "sign"]
    if beside is None:
        return RecordedSign(gloss, dofs, rate_hz, (0, len(dofs) - 1), simulated)
    if len(signs) != 1 or signs[0].end_frame >= len(dofs):
        raise LexiconError(
            f"{beside}: a recorded sign's segmentation marks one sign within its "
            f"{len(dofs)} frames."
        )
    return RecordedSign(gloss, dofs, rate_hz, (signs[0].start_frame, signs[0].end_frame), simulated)


def write_lexicon(recordings, out: str | Path, simulated: bool = False, glosses=None) -> Path:
    """Write the manifest of *recordings* (paths) to *out*.

    Each gloss is its file's name in capitals unless *glosses* gives them in order.
    """
    out = Path(out)
    recordings = [Path(p) for p in recordings]
    glosses = glosses or [p.name.split(".")[0].upper() for p in recordings]
    if len(glosses) != len(recordings):
        raise LexiconError(f"{len(recordings)} recordings but {len(glosses)} glosses.")
    signs = {}
    for gloss, path in zip(glosses, recordings, strict=True):
        read_sign(path)  # refuse a bad recording now, not at render time
        signs[gloss] = {
            "file": os.path.relpath(path.resolve(), out.parent.resolve()),
            "sha256": _sha256(path),
        }
    data = {"format": FORMAT, "version": FORMAT_VERSION, "simulated": simulated, "signs": signs}
    out.write_text(json.dumps(data, indent=1) + "\n", "utf-8")
    return out


def read_lexicon(path: str | Path) -> SignLexicon:
    """Return the lexicon at *path*; raise :class:`LexiconError` naming the problem."""
    path = Path(path)
    try:
        data = json.loads(path.read_text("utf-8"))
    except (OSError, UnicodeDecodeError, json.JSONDecodeError) as error:
        raise LexiconError(f"{path}: cannot be read as JSON ({error}).") from None
    check_header(data, FORMAT, FORMAT_VERSION, "sign lexicon", LexiconError, str(path))
    if not isinstance(data.get("signs"), dict):
        raise LexiconError(f"{path}: a sign lexicon needs a 'signs' table.")
    signs = {}
    for gloss, entry in data["signs"].items():
        try:
            recording = path.parent / entry["file"]
            digest = _sha256(recording)
        except (KeyError, TypeError, OSError) as error:
            raise LexiconError(
                f"{path}: the recording of {gloss} cannot be read ({error})."
            ) from None
        if digest != entry.get("sha256"):
            raise LexiconError(
                f"{path}: {recording} changed since the lexicon was written; "
                "write the lexicon again."
            )
        signs[gloss] = read_sign(recording, gloss, data.get("simulated") is True)
    if not signs:
        raise LexiconError(f"{path}: the lexicon holds no signs.")
    return SignLexicon(signs, str(path))


def simulated_lexicon(
    glosses,
    directory: str | Path,
    seed: int = 0,
    rate_hz: float = 120.0,
    attack_ms: float = 0.0,
) -> Path:
    """Write simulated recordings of *glosses* (the engine's signs from rest to rest, with
    liveliness noise; labelled simulated) and their lexicon; return the manifest's path.

    *attack_ms* > 0 holds the rest before and after each sign until its attack and decay
    last that long, as seed 004 §3.1.3's recordings did (1 s each), so that its 1 s blend
    overlap applies to them.
    """
    from synthesis.signing.sentence import SentenceOptions, synthesize
    from synthesis.transitions.segments import Segment, Segmentation

    directory = Path(directory)
    paths = []
    for k, gloss in enumerate(glosses):
        sentence = synthesize(gloss, SentenceOptions(rate_hz=rate_hz, seed=seed + k))
        frames = round(attack_ms * rate_hz / 1000)
        dofs, (first, last) = _rest_held(sentence.dofs_rad, sentence.token_frames()[0], frames)
        n = len(dofs)
        segments = (
            Segment("rest", 1, 0, int(first) - 1, "attack"),
            Segment("sign", 2, int(first), int(last), gloss),
            Segment("rest", 3, int(last) + 1, n - 1, "decay"),
        )
        name = gloss.lower().replace("'", "")
        recording = SegmentedRecording(
            name,
            dofs,
            tuple(sentence.body.dof_names),
            rate_hz,
            Segmentation(name, segments),
            "sim",
            True,
        )
        paths.append(write_recording(recording, directory))
    return write_lexicon(paths, directory / "lexicon.json", simulated=True, glosses=list(glosses))


def _rest_held(dofs: np.ndarray, sign: np.ndarray, frames: int) -> tuple[np.ndarray, tuple]:
    """Return *dofs* with the first and last frame (at rest) held until the attack before
    the *sign*'s first frame and the decay after its last are *frames* long each, and the
    sign's frames moved with them."""
    first, last = int(sign[0]), int(sign[1])
    before = max(0, frames - first)
    after = max(0, frames - (len(dofs) - 1 - last))
    held = np.concatenate([np.repeat(dofs[:1], before, 0), dofs, np.repeat(dofs[-1:], after, 0)])
    return held, (first + before, last + before)


def _eased(v0: np.ndarray, v1: np.ndarray, n_frames: int) -> np.ndarray:
    """Return *n_frames* easing from v0 to v1 (smoothstep), exclusive of both ends."""
    s = np.arange(1, n_frames + 1) / (n_frames + 1)
    return v0 + np.outer(3 * s**2 - 2 * s**3, v1 - v0)


def assemble(
    glosses, lexicon: SignLexicon, rate_hz: float, gap_ms: float = GAP_MS, side: str = "right"
) -> Sentence:
    """Return a sentence of recorded signs played as recorded, eased from one to the next.

    The first sign's attack and the last one's decay are kept (from and back to rest);
    between signs, every DOF eases over *gap_ms*. The signs' frames are never changed.
    """
    signs = [lexicon.sign(g).resampled(rate_hz) for g in glosses]
    gap = max(1, round(gap_ms / 1000 * rate_hz) - 1)
    first, last = signs[0], signs[-1]
    parts = [first.dofs_rad[: first.sign_frames[0]]]
    tokens = []
    for k, sign in enumerate(signs):
        if k:
            parts.append(_eased(parts[-1][-1], sign.sign[0], gap))
        start = sum(len(p) for p in parts)
        parts.append(sign.sign)
        tokens.append((start, start + len(sign.sign) - 1))
    parts.append(last.dofs_rad[last.sign_frames[1] + 1 :])
    body = BodyModel(side)
    dofs = np.vstack([p for p in parts if len(p)])
    if side == "left":
        dofs = body.mirror_pose(dofs)
    tokens_s = np.array(tokens, dtype=float) / rate_hz
    return Sentence(
        body,
        body.clip(dofs),
        np.zeros_like(dofs),
        rate_hz,
        tokens_s.ravel(),
        tuple(glosses),
        tokens_s=tokens_s,
    )


def blend_recorded(
    glosses,
    lexicon: SignLexicon,
    rate_hz: float,
    side: str = "right",
    overlap_ms: float | None = None,
) -> tuple[np.ndarray, int]:
    """Return the whole recorded clips blended (seed 004 §4.1), and the overlap in frames.

    By default the overlap is the shortest marked attack or decay, so no blend reaches a
    sign; *overlap_ms* fixes it instead, as the seed does (1 s, its recordings' own attack
    and decay), and one longer than half a recording is refused, naming it.
    """
    signs = [lexicon.sign(g).resampled(rate_hz) for g in glosses]
    if len(signs) == 1:
        return signs[0].dofs_rad, 0
    if overlap_ms is not None:
        overlap = round(overlap_ms * rate_hz / 1000)
        short = [g for g, s in zip(glosses, signs, strict=True) if len(s.dofs_rad) < 2 * overlap]
        if short:
            raise LexiconError(
                f"A {overlap_ms:g} ms overlap needs recordings of at least {2 * overlap_ms:g} "
                f"ms (an attack and a decay); {', '.join(short)} is shorter."
            )
    else:
        attacks = [s.sign_frames[0] for s in signs[1:]]
        decays = [len(s.dofs_rad) - 1 - s.sign_frames[1] for s in signs[:-1]]
        overlap = min(attacks + decays)
        if overlap < 1:
            raise LexiconError(
                "Blending needs each recording's attack and decay marked: segment "
                "the recordings (rest, sign, rest)."
            )
    dofs = blend_signs([s.dofs_rad for s in signs], overlap)
    body = BodyModel(side)
    return (body.mirror_pose(dofs) if side == "left" else dofs), overlap
