"""Non-manual signals: brows, eyes, mouth and head over spans of glosses (seed 003 §4).

A sentence's text marks a span of glosses with a signal in brackets, the way a gloss
transcription draws a line over them: ``I LOST [rhq WHERE]``, ``[q HAVE C-A-R]?``,
``[neg:0.5 CAN'T FIND]`` (half intensity). A sign may carry its own (``nonmanual: cha``
in the sign library: BIG's puffed, wide-open mouth). Each signal is a :class:`Marker`
of the library: face poses (:data:`synthesis.rigs.face.EXPRESSIONS`, or face DOFs) and
held head angles at full intensity, and perhaps a head oscillation (a shake for
negation, a nod for assertion); it rises over *onset_ms* before its span's first sign
(non-manual signals lead the hands, Baker-Shenk & Cokely 1980), holds to the span's
last, and falls over *offset_ms*. The signer blinks at each phrase boundary
(punctuation in the text).

Everything here moves *face channels*: the face's DOFs and the head joint's (the neck
and spine are left to the sentence and the spine technique), so turning the face off
changes nothing else.
"""

import re
from collections.abc import Mapping
from dataclasses import dataclass, field

import numpy as np

from synthesis.rigs.face import EXPRESSIONS, is_face_dof

HEAD_DOFS = ("head_flexion", "head_side_bend", "head_rotation")
# A blink (ms): the lid shuts fast and opens more slowly (about 100 + 150 ms).
BLINK_CLOSE_MS, BLINK_OPEN_MS = 100.0, 150.0
BLINK_DEGREES = {**EXPRESSIONS["blink"]}
_SPAN = re.compile(r"\[|\]|[^\s\[\]]+")
_MARKER = re.compile(r"^([a-z][a-z0-9-]*)(?::([0-9]*\.?[0-9]+))?$")


class NonmanualError(ValueError):
    """A malformed non-manual signal: an unknown marker, an unclosed span, …"""


@dataclass(frozen=True)
class Marker:
    """One non-manual signal at full intensity.

    *face_deg* face DOFs and *head_deg* head angles (flexion, side_bend, rotation) held
    over the span, degrees; *oscillation* a head DOF swung over the span (its name, peak
    degrees, cycles per second) or None.
    """

    name: str
    label: str
    face_deg: Mapping[str, float] = field(default_factory=dict)
    head_deg: Mapping[str, float] = field(default_factory=dict)
    oscillation: tuple[str, float, float] | None = None
    onset_ms: float = 150.0
    offset_ms: float = 200.0


@dataclass(frozen=True)
class Span:
    """A marker over tokens *first*…*last* (indices into the sentence's glosses)."""

    marker: str
    first: int
    last: int
    intensity: float = 1.0


@dataclass(frozen=True)
class Track:
    """A marker placed in time: from *start_ms* to *end_ms* of the sentence, at *intensity*."""

    marker: str
    start_ms: float
    end_ms: float
    intensity: float = 1.0


def parse_markers(entries) -> dict[str, Marker]:
    """Return the library's markers from its ``nonmanuals`` section; NonmanualError names
    what is wrong."""
    markers = {}
    for name, entry in (entries or {}).items():
        where = f"Non-manual signal {name!r}"
        if not isinstance(entry, dict):
            raise NonmanualError(f"{where}: expected a mapping.")
        face = {}
        for pose, value in (entry.get("face") or {}).items():
            if pose in EXPRESSIONS:
                for dof, degrees in EXPRESSIONS[pose].items():
                    face[dof] = face.get(dof, 0.0) + float(value) * degrees
            elif is_face_dof(pose):
                face[pose] = face.get(pose, 0.0) + float(value)
            else:
                raise NonmanualError(f"{where}: unknown face pose or channel {pose!r}.")
        head = {f"head_{k}": float(v) for k, v in (entry.get("head") or {}).items()}
        unknown = set(head) - set(HEAD_DOFS)
        if unknown:
            raise NonmanualError(f"{where}: unknown head angle {sorted(unknown)[0]!r}.")
        oscillation = None
        if entry.get("oscillate"):
            swing = entry["oscillate"]
            dof = f"head_{swing.get('angle')}"
            if dof not in HEAD_DOFS:
                raise NonmanualError(f"{where}: unknown head angle {swing.get('angle')!r}.")
            oscillation = (dof, float(swing.get("deg", 8.0)), float(swing.get("hz", 2.0)))
        markers[str(name)] = Marker(
            str(name),
            str(entry.get("label", name)),
            face,
            head,
            oscillation,
            float(entry.get("onset_ms", 150.0)),
            float(entry.get("offset_ms", 200.0)),
        )
    return markers


def parse_spans(text: str) -> tuple[str, list[Span], set[int]]:
    """Return the text without its brackets, the spans they mark, and the phrase
    boundaries (indices of the tokens a punctuation mark follows).

    ``"I LOST [rhq WHERE]. I SEARCH"`` → ``"I LOST WHERE. I SEARCH"``, one span over
    token 2, a boundary after token 2. Spans nest; a marker is ``name`` or
    ``name:intensity``.
    """
    words, spans, open_spans, boundaries = [], [], [], set()
    pieces = _SPAN.findall(text)
    k = 0
    while k < len(pieces):
        piece = pieces[k]
        if piece == "[":
            if k + 1 >= len(pieces) or pieces[k + 1] in "[]":
                raise NonmanualError("A '[' must be followed by a non-manual marker.")
            match = _MARKER.match(pieces[k + 1])
            if not match:
                raise NonmanualError(f"{pieces[k + 1]!r} is not a non-manual marker.")
            open_spans.append((match.group(1), float(match.group(2) or 1.0), _count(words)))
            k += 2
            continue
        if piece == "]":
            if not open_spans:
                raise NonmanualError("A ']' closes no non-manual span.")
            name, intensity, first = open_spans.pop()
            if _count(words) == first:
                raise NonmanualError(f"The [{name} …] span holds no signs.")
            spans.append(Span(name, first, _count(words) - 1, intensity))
        else:
            words.append(piece)
            if re.search(r"[,.!?;:—–]$", piece) and _count(words):
                boundaries.add(_count(words) - 1)
        k += 1
    if open_spans:
        raise NonmanualError(f"The [{open_spans[-1][0]} …] span is not closed.")
    return " ".join(words), spans, boundaries


def _count(words: list[str]) -> int:
    """Return how many gloss tokens *words* hold, counted as parse_glosses counts them."""
    return sum(1 for word in words if word.strip(',.!?;:—–"') not in ("", "-"))


def envelope(at_ms: np.ndarray, track: Track, marker: Marker) -> np.ndarray:
    """Return the track's intensity at times (n,) ms: eased up over the marker's onset
    before *start_ms*, held, eased down over its offset after *end_ms*."""
    rise = _ease((at_ms - (track.start_ms - marker.onset_ms)) / max(marker.onset_ms, 1.0))
    fall = _ease(((track.end_ms + marker.offset_ms) - at_ms) / max(marker.offset_ms, 1.0))
    return track.intensity * np.minimum(rise, fall)


def _ease(x: np.ndarray) -> np.ndarray:
    x = np.clip(x, 0.0, 1.0)
    return x * x * (3 - 2 * x)


def nonmanual_channels(
    dof_names: list[str], markers: Mapping[str, Marker], tracks, at_s: np.ndarray
) -> np.ndarray:
    """Return the tracks' face channels (n_frames, n_dofs) in radians, summed."""
    index = {name: i for i, name in enumerate(dof_names)}
    at_ms = np.asarray(at_s, dtype=np.float64) * 1000.0
    out = np.zeros((len(at_ms), len(dof_names)))
    for track in tracks:
        marker = markers[track.marker]
        weight = envelope(at_ms, track, marker)
        for dof, degrees in {**marker.face_deg, **marker.head_deg}.items():
            out[:, index[dof]] += np.radians(degrees) * weight
        if marker.oscillation is not None:
            dof, degrees, rate_hz = marker.oscillation
            phase = 2 * np.pi * rate_hz * (at_ms - (track.start_ms - marker.onset_ms)) / 1000
            out[:, index[dof]] += np.radians(degrees) * weight * np.sin(phase)
    return out


def blink_channels(dof_names: list[str], blink_ms, at_s: np.ndarray) -> np.ndarray:
    """Return blinks starting at times *blink_ms* as face channels (n_frames, n_dofs)."""
    index = {name: i for i, name in enumerate(dof_names)}
    at_ms = np.asarray(at_s, dtype=np.float64) * 1000.0
    closed = np.zeros(len(at_ms))
    for start in blink_ms:
        shut = _ease((at_ms - start) / BLINK_CLOSE_MS)
        opened = _ease((at_ms - start - BLINK_CLOSE_MS) / BLINK_OPEN_MS)
        closed = np.maximum(closed, shut - opened)
    out = np.zeros((len(at_ms), len(dof_names)))
    for dof, degrees in BLINK_DEGREES.items():
        out[:, index[dof]] = np.radians(degrees) * closed
    return out
