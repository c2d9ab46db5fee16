"""Read a sentence recording's segmentation into signs and transitions (seed 001 §3.2, §5.2.1).

Three layouts are read, all into :class:`Segmentation`:

- the well-formed XML seed 001 §5.2.1 proposes:
  ``<sseg><sentence number="1"><segment type="sign" order="1" start="0" end="40"
  label="HELLO"/>…</sentence></sseg>``;
- the seed's original files (Code 3.1), one element per segment named by its sign
  (``<Ola end="355" pos="3" start="293" word="True"/>``, transitions ``TRANSITIONn``,
  the approach and return ``Intro``/``End``);
- JSON: ``{"sentences": [{"number": 1, "segments": [{"type": "sign", "order": 1,
  "start": 0, "end": 40, "label": "HELLO"}]}]}``.

Frames are closed intervals ``[start, end]``. Every problem raises one
:class:`SegmentationError` naming the sentence and the segment.
"""

import itertools
import json
import xml.etree.ElementTree as ElementTree
from dataclasses import dataclass

KINDS = ("sign", "transition", "rest")


class SegmentationError(ValueError):
    """A segmentation that cannot be read or does not describe a recording."""


@dataclass(frozen=True)
class Segment:
    """One interval of a sentence recording: a sign, a transition or rest (approach/return)."""

    kind: str
    order: int
    start_frame: int
    end_frame: int
    label: str = ""

    @property
    def n_frames(self) -> int:
        """Return the number of frames in the closed interval."""
        return self.end_frame - self.start_frame + 1


@dataclass(frozen=True)
class Segmentation:
    """A sentence's segments in order; see :func:`check_segmentation` for its rules."""

    sentence: str
    segments: tuple[Segment, ...]

    def transitions(self) -> tuple[tuple[Segment, Segment, Segment], ...]:
        """Return each transition with the signs before and after it."""
        found = []
        for before, middle, after in zip(
            self.segments, self.segments[1:], self.segments[2:], strict=False
        ):
            if middle.kind == "transition" and before.kind == after.kind == "sign":
                found.append((before, middle, after))
        return tuple(found)


def _integer(value, what: str) -> int:
    if isinstance(value, bool):
        raise SegmentationError(f"{what} is not a whole number: {value!r}.")
    if isinstance(value, int):
        return value
    if isinstance(value, str) and value.strip().isascii() and value.strip().isdigit():
        return int(value.strip())
    raise SegmentationError(f"{what} is not a whole number: {value!r}.")


def _segment(raw: dict, where: str) -> Segment:
    kind = raw.get("type")
    if kind not in KINDS:
        raise SegmentationError(f"{where}: type {kind!r} is not one of {', '.join(KINDS)}.")
    missing = [name for name in ("order", "start", "end") if raw.get(name) in (None, "")]
    if missing:
        raise SegmentationError(f"{where}: no {', '.join(missing)}.")
    label = raw.get("label", "")
    if not isinstance(label, str):
        raise SegmentationError(f"{where}: the label is not text.")
    return Segment(
        kind,
        _integer(raw["order"], f"{where}: order"),
        _integer(raw["start"], f"{where}: start"),
        _integer(raw["end"], f"{where}: end"),
        label,
    )


def check_segmentation(segmentation: Segmentation, n_frames: int | None = None) -> Segmentation:
    """Return *segmentation* with its segments in order, or raise SegmentationError.

    Orders are 1, 2, … without gaps or repeats; each segment starts no later than it
    ends; segments follow each other in time without overlapping; with *n_frames*, none
    reaches past the recording's last frame.
    """
    name = segmentation.sentence
    segments = sorted(segmentation.segments, key=lambda s: s.order)
    if not segments:
        raise SegmentationError(f"Sentence {name}: no segments.")
    orders = [s.order for s in segments]
    if orders != list(range(1, len(segments) + 1)):
        raise SegmentationError(
            f"Sentence {name}: the segments' orders must be 1 to {len(segments)} without "
            f"gaps or repeats; got {orders}."
        )
    for segment in segments:
        where = f"Sentence {name}, segment {segment.order} ({segment.label or segment.kind})"
        if segment.start_frame > segment.end_frame:
            raise SegmentationError(
                f"{where} starts at frame {segment.start_frame}, after its end {segment.end_frame}."
            )
        if n_frames is not None and segment.end_frame >= n_frames:
            raise SegmentationError(
                f"{where} ends at frame {segment.end_frame}, but the recording's last "
                f"frame is {n_frames - 1}."
            )
    for before, after in itertools.pairwise(segments):
        if after.start_frame <= before.end_frame:
            raise SegmentationError(
                f"Sentence {name}: segment {after.order} ({after.label or after.kind}) starts "
                f"at frame {after.start_frame}, within segment {before.order} "
                f"({before.label or before.kind}), which ends at {before.end_frame}."
            )
    return Segmentation(name, tuple(segments))


def _from_xml(text: str) -> list[Segmentation]:
    try:
        root = ElementTree.fromstring(text)
    except ElementTree.ParseError as error:
        raise SegmentationError(f"Not well-formed XML ({error}).") from None
    sentences = []
    for number, element in enumerate(root, 1):
        if element.tag == "sentence":
            name = element.get("number", str(number))
            raws = [dict(child.attrib) for child in element if child.tag == "segment"]
            if len(raws) != len(element):
                raise SegmentationError(f"Sentence {name}: every child must be a <segment>.")
        else:  # the seed's original layout: elements named by their sign
            name = element.tag
            raws = [_original(child) for child in element]
        segments = tuple(
            _segment(raw, f"Sentence {name}, segment {i}") for i, raw in enumerate(raws, 1)
        )
        sentences.append(check_segmentation(Segmentation(name, segments)))
    return sentences


def _original(child) -> dict:
    """Return a segment of the seed's Code 3.1 layout in the proposed layout's terms."""
    word = child.get("word", "").strip().lower()
    if word == "true":
        kind = "sign"
    elif child.tag.upper().startswith("TRANSITION"):
        kind = "transition"
    elif word == "false":
        kind = "rest"
    else:
        kind = None
    return {
        "type": kind,
        "order": child.get("pos"),
        "start": child.get("start"),
        "end": child.get("end"),
        "label": child.tag,
    }


def _from_json(text: str) -> list[Segmentation]:
    try:
        data = json.loads(text)
    except json.JSONDecodeError as error:
        raise SegmentationError(f"Not valid JSON ({error.msg}, line {error.lineno}).") from None
    if not isinstance(data, dict) or not isinstance(data.get("sentences"), list):
        raise SegmentationError('A JSON segmentation is an object with a "sentences" list.')
    sentences = []
    for number, sentence in enumerate(data["sentences"], 1):
        if not isinstance(sentence, dict) or not isinstance(sentence.get("segments"), list):
            raise SegmentationError(f'Sentence {number}: needs a "segments" list.')
        name = str(sentence.get("number", number))
        raws = sentence["segments"]
        for i, raw in enumerate(raws, 1):
            if not isinstance(raw, dict):
                raise SegmentationError(f"Sentence {name}, segment {i}: not an object.")
        segments = tuple(
            _segment(raw, f"Sentence {name}, segment {i}") for i, raw in enumerate(raws, 1)
        )
        sentences.append(check_segmentation(Segmentation(name, segments)))
    return sentences


def parse_segmentation(text: str) -> list[Segmentation]:
    """Return the sentences of a segmentation given as XML or JSON text."""
    stripped = text.lstrip()
    if not stripped:
        raise SegmentationError("The segmentation is empty.")
    sentences = _from_json(text) if stripped[0] in "{[" else _from_xml(text)
    if not sentences:
        raise SegmentationError("The segmentation has no sentences.")
    return sentences
