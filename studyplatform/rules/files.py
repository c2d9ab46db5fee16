"""Check a study's file settings: references to stored objects its owner may use, never paths.

A technique parameter of type ``file`` names a file the engine reads. On the command line
that is a path; on the platform it is a reference, ``<kind>:<id>``, to an object the
platform stores for researchers (a word's recording, an avatar), resolved to its file
by the platform when a clip is specified and usable only by a study whose owner owns the
object (any, for a superuser's study). An absolute path, ``..`` or someone else's object
is refused naming the parameter (issue 51: ``recording=<var>/secret_key`` once read the
server's key into an error message). Parameters without a stored kind are the engine's
alone: the platform keeps them empty.

The objects are looked up through Django's app registry, so this rule, like the others,
imports no model.
"""

import functools
import re
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from django.apps import apps
from django.core.exceptions import ValidationError
from django.utils.translation import gettext, gettext_noop

from synthesis.techniques import REGISTRY, ClipError


@dataclass(frozen=True)
class FileSource:
    """A kind of stored object that a file parameter may name, and how to find its file."""

    kind: str  # the reference's prefix: "recording" in "recording:12"
    model: str  # the model's name in the studyplatform app
    owner: str  # the lookup from a row to the researcher who owns it
    file_field: str  # the field holding the file the engine reads
    ready: Mapping[str, Any]  # what makes a row usable, as lookups
    where: str  # where a researcher finds the object's id

    def describe(self) -> str:
        return f"{self.kind}:<id> ({gettext(self.where)})"


RECORDING = FileSource(
    "recording",
    "Recording",
    "item__study__owner",
    "motion",
    {"status": "ready"},
    gettext_noop("a ready recording on a word's Recordings page"),
)
AVATAR = FileSource("avatar", "Avatar", "owner", "file", {}, gettext_noop("one of your Avatars"))

# Which stored kinds each file parameter takes (studyplatform.checks holds it to the
# registry). A file parameter not named here takes none: the platform keeps it empty.
FILE_SOURCES: dict[str, tuple[FileSource, ...]] = {
    "recording": (RECORDING,),
    "avatar_file": (AVATAR,),
}

REFERENCE = re.compile(r"(?P<kind>[a-z_]+):(?P<pk>[1-9][0-9]{0,17})")


@functools.cache  # the registry is fixed once imported; every clip spec asks
def file_parameters() -> dict[str, str]:
    """Return every technique parameter of type file, with the technique declaring it."""
    return {
        parameter.name: technique.name
        for technique in REGISTRY.techniques
        for parameter in technique.parameters
        if parameter.type == "file"
    }


def file_help(name: str) -> str:
    """Return what file parameter *name* takes on the platform, for its form field."""
    sources = FILE_SOURCES.get(name, ())
    if not sources:
        return gettext("The engine's command line only: leave it empty here.")
    shown = gettext(" or ").join(source.describe() for source in sources)
    return gettext("Names a stored file: %(sources)s; empty: none.") % {"sources": shown}


def _owned_row(source: FileSource, pk: int, owner):
    """Return the *source* row *pk* that *owner* may use, or None."""
    if owner is None:
        return None
    model = apps.get_model("studyplatform", source.model)
    rows = model.objects.filter(pk=pk, **source.ready).exclude(**{source.file_field: ""})
    if not owner.is_superuser:
        rows = rows.filter(**{source.owner: owner})
    return rows.first()


def _resolve_one(name: str, value: Any, owner) -> str:
    """Return the file that file parameter *name*'s *value* names, or raise ClipError."""
    sources = FILE_SOURCES.get(name, ())
    if not sources:
        raise ClipError(
            gettext(
                "%(name)s names a file on the rendering machine, which the platform does not "
                "open for researchers: leave it empty here (the engine's command line takes "
                "a path)."
            )
            % {"name": name}
        )
    shown = gettext(" or ").join(source.describe() for source in sources)
    match = REFERENCE.fullmatch(value) if isinstance(value, str) else None
    by_kind = {source.kind: source for source in sources}
    if match is None or match["kind"] not in by_kind:
        raise ClipError(
            gettext(
                "%(name)s must name a stored file as %(shown)s, not %(value)r: the platform "
                "takes no paths."
            )
            % {"name": name, "shown": shown, "value": str(value)[:80]}
        )
    source = by_kind[match["kind"]]
    row = _owned_row(source, int(match["pk"]), owner)
    if row is None:
        raise ClipError(
            gettext("%(name)s: no %(kind)s %(pk)s that this study's owner may use (use %(shown)s).")
            % {"name": name, "kind": source.kind, "pk": match["pk"], "shown": source.describe()}
        )
    return getattr(row, source.file_field).path


def file_settings(parameters: Any) -> dict[str, Any]:
    """Return the file parameters set in *parameters* (a non-mapping has none)."""
    if not isinstance(parameters, Mapping):
        return {}
    names = file_parameters()
    return {name: value for name, value in parameters.items() if name in names and value}


def resolve_files(parameters: Mapping[str, Any], owner) -> dict[str, Any]:
    """Return *parameters* with each file reference replaced by its stored file's path.

    Raise ClipError naming the parameter when a value is not a reference to an object
    *owner* may use. Only the platform's own resolution makes paths.
    """
    resolved = dict(parameters)
    for name, value in file_settings(parameters).items():
        resolved[name] = _resolve_one(name, value, owner)
    return resolved


def check_files(parameters: Any, owner) -> None:
    """Raise ValidationError on ``parameters`` if a file setting is not a reference
    *owner* may use."""
    try:
        resolve_files(file_settings(parameters), owner)
    except ClipError as error:
        raise ValidationError({"parameters": str(error)}) from None
