"""The registry of techniques and item kinds: what a condition may set, and for what.

A :class:`Technique` is one manipulation a study can compare (a timing model, spine
on/off, …): its parameters as data, the item kinds it applies to, the seed it draws
from, and the step it adds to building a clip's motion. An :class:`ItemKind` is signed
content the engine renders (a fingerspelled word, a sentence): its views and the step
that turns the techniques' work into a motion. Everything that offers or checks
parameters — validation, the command line, the admin form, the study schema, the clip
hash — reads them from :data:`REGISTRY`.

Add a technique: write its module (a ``TECHNIQUE = Technique(...)``) and name it in
:func:`synthesis.techniques.default.default_registry`. Tests add one for a while with
:meth:`Registry.registered`.
"""

from collections.abc import Callable, Iterator, Mapping
from contextlib import contextmanager
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from synthesis.techniques.parameters import ClipError, Parameter

if TYPE_CHECKING:  # request.py builds on this module
    from synthesis.techniques.request import Build

PREPARE, MOTION = "prepare", "motion"


@dataclass(frozen=True)
class Technique:
    """One technique a study compares, declared as data.

    *apply* takes and returns a :class:`~synthesis.techniques.request.Build`: in the
    ``prepare`` stage before the item kind makes the motion (choosing a performance, a
    timing, synthesis options), in the ``motion`` stage after it (changing the motion).
    *check* refuses combinations of values (it raises :class:`ClipError`). *order*
    sorts the techniques of a stage. *chooses_content* marks a technique that chooses
    what is signed, by whom or when (a source, a timing, an avatar), not how the motion
    is made between keys: the stimulus check's keyed reference keeps its values and
    resets the others' (:mod:`synthesis.quality`). *reference_keeps* names parameters of
    a motion technique the reference keeps all the same: those that choose which joints
    carry the motion (the spine on or off), not how fast.
    """

    name: str
    label: str
    kinds: frozenset[str]
    parameters: tuple[Parameter, ...]
    source: str = ""
    stage: str = PREPARE
    order: int = 50
    apply: Callable[["Build"], "Build"] | None = None
    check: Callable[[Mapping[str, Any]], None] | None = None
    summary: Callable[[Mapping[str, Any]], str] | None = None
    chooses_content: bool = False
    reference_keeps: tuple[str, ...] = ()

    def describe(self, values: Mapping[str, Any]) -> str:
        """Return what this technique does with *values*, in plain words.

        By default: its first parameter's value, then every other that is not the default.
        """
        if self.summary is not None:
            return f"{self.label}: {self.summary(values)}"
        first, *rest = self.parameters
        words = [first.label_of(values[first.name])]
        words += [
            f"{p.name.replace('_', ' ')} {p.label_of(values[p.name])}"
            for p in rest
            if values[p.name] != p.default
        ]
        return f"{self.label}: {', '.join(words)}"


@dataclass(frozen=True)
class ItemKind:
    """Signed content the engine renders, and how its motion is made.

    *start* turns a request into the first build; *finish* makes the motion from what
    the prepare-stage techniques chose, for the rig of the clip's view; *check_text*
    refuses a text the kind cannot sign with the techniques' values (a word's letters
    in its alphabet; it raises :class:`ClipError`), before any rendering.
    """

    name: str
    label: str
    views: tuple[str, ...]
    start: Callable[["Build"], "Build"]
    finish: Callable[["Build"], "Build"]
    check_text: Callable[[str, Mapping[str, Any]], None] | None = None

    @property
    def default_view(self) -> str:
        return self.views[0]


@dataclass
class Registry:
    """The techniques and item kinds the engine knows, in pipeline order."""

    kinds: dict[str, ItemKind] = field(default_factory=dict)
    techniques: list[Technique] = field(default_factory=list)

    def kind(self, name: str) -> ItemKind:
        """Return the item kind *name*, or raise :class:`ClipError` naming the known ones."""
        try:
            return self.kinds[name]
        except (KeyError, TypeError):
            *others, last = self.kinds
            raise ClipError(
                f"Unknown item kind {name!r}: the kinds are {', '.join(others)} and {last}."
            ) from None

    def check_text(self, kind: str, text: str, values: Mapping[str, Any] | None = None) -> None:
        """Raise :class:`ClipError` when an item of *kind* cannot sign *text* with the
        techniques' *values* (checked and completed with their defaults first)."""
        item_kind = self.kind(kind)
        if item_kind.check_text is not None:
            item_kind.check_text(text, self.normalize(kind, values or {}))

    def for_kind(self, kind: str) -> list[Technique]:
        """Return the techniques that apply to items of *kind*."""
        self.kind(kind)
        return [t for t in self.techniques if kind in t.kinds]

    def parameters(self, kind: str | None = None) -> dict[str, tuple[Parameter, Technique]]:
        """Return each parameter name with its declaration and technique (of *kind*)."""
        techniques = self.techniques if kind is None else self.for_kind(kind)
        return {p.name: (p, t) for t in techniques for p in t.parameters}

    def normalize(self, kind: str, values: Mapping[str, Any]) -> dict[str, Any]:
        """Return *values* checked and completed with defaults for an item of *kind*.

        Raise :class:`ClipError` naming the first problem: an unknown item kind, an
        unknown parameter, a parameter of a technique that does not apply to *kind*, a
        value of the wrong type or out of range, or a combination a technique refuses.
        """
        item_kind = self.kind(kind)
        if not isinstance(values, Mapping):
            raise ClipError(f"Parameters must be a mapping of names to values, not {values!r}.")
        known, everywhere = self.parameters(kind), self.parameters()
        result = {}
        for name, value in values.items():
            if name not in known:
                if name in everywhere:
                    _, technique = everywhere[name]
                    kinds = " or ".join(self.kinds[k].label for k in sorted(technique.kinds))
                    raise ClipError(
                        f"Parameter {name!r} ({technique.label}) does not apply to a "
                        f"{item_kind.label}; it applies to a {kinds}."
                    )
                raise ClipError(
                    f"Unknown parameter {name!r} for a {item_kind.label}; "
                    f"known: {', '.join(sorted(known))}."
                )
            result[name] = known[name][0].check(value)
        for name, (parameter, _) in known.items():
            result.setdefault(name, parameter.default)
        for technique in self.for_kind(kind):
            if technique.check is not None:
                technique.check(result)
        return dict(sorted(result.items()))

    def describe(self, kind: str, values: Mapping[str, Any]) -> list[str]:
        """Return, per technique of *kind*, what *values* make it do, in plain words."""
        values = self.normalize(kind, values)
        return [t.describe(values) for t in self.for_kind(kind)]

    def schema(self) -> dict:
        """Return the JSON Schema of condition and item parameters, by item kind."""
        return {
            name: {
                "type": "object",
                "title": kind.label,
                "additionalProperties": False,
                "properties": {p: d.schema() for p, (d, _) in self.parameters(name).items()},
            }
            for name, kind in self.kinds.items()
        }

    @contextmanager
    def registered(self, technique: Technique) -> Iterator[Technique]:
        """Register *technique* for the duration of a ``with`` block (for tests and tools)."""
        if any(t.name == technique.name for t in self.techniques):
            raise ValueError(f"A technique named {technique.name!r} is registered already.")
        self.techniques.append(technique)
        try:
            yield technique
        finally:
            self.techniques.remove(technique)
