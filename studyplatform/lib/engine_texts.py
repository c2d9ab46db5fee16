"""Collect the engine's texts the researcher's pages show, for the interface's catalogues.

The engine never imports Django, so its names and help (techniques, their parameters and
choices, manual alphabets, the builder's designs) are plain English strings in its
registries. ``manage.py write_engine_texts`` writes them into
``studyplatform/admin/engine_texts.py`` as ``gettext_noop`` calls, where makemessages
finds them; the admin shows each through ``gettext``. A test fails when that module is
out of date with the registries.
"""

from stimuli.plan import Design
from synthesis.fingerspelling.alphabets import alphabet_choices
from synthesis.techniques import REGISTRY, REQUEST_PARAMETERS, Parameter

MODULE = "studyplatform/admin/engine_texts.py"


def parameter_title(parameter: Parameter) -> str:
    """Return the name a form gives *parameter* (its identifier in words)."""
    return parameter.name.replace("_", " ").capitalize()


def engine_texts() -> list[str]:
    """Return every engine text the admin shows, once each, in registry order."""
    texts: list[str] = []
    parameters = [p for t in REGISTRY.techniques for p in t.parameters]
    for parameter in [*parameters, *REQUEST_PARAMETERS]:
        labels = parameter.labels or {}
        shown = [labels.get(value, str(value)) for value in parameter.choices or ()]
        texts += [parameter_title(parameter), parameter.help, *shown, parameter.units or ""]
    texts += [t.label for t in REGISTRY.techniques]
    texts += [name for _, name in alphabet_choices()]
    texts += [design.label for design in Design]
    return [text for text in dict.fromkeys(texts) if text]


def engine_texts_module() -> str:
    """Return the source of the module that marks :func:`engine_texts` for translation."""
    lines = [
        '"""The engine\'s texts the researcher\'s pages show, marked for the catalogues.',
        "",
        "Written by ``manage.py write_engine_texts`` from the engine's registries",
        "(studyplatform/lib/engine_texts.py); do not edit it by hand.",
        '"""',
        "",
        "from django.utils.translation import gettext_noop",
        "",
        "TEXTS = (",
        *(_marked(text) for text in engine_texts()),
        ")",
        "",
    ]
    return "\n".join(lines)


def _marked(text: str, width: int = 84) -> str:
    """Return *text* as a ``gettext_noop`` line, split into pieces that fit the line."""
    if len(text) <= width - 8:
        return f"    gettext_noop({text!r}),"
    pieces, piece = [], ""
    for word in text.split(" "):
        if piece and len(piece) + len(word) + 1 > width:
            pieces.append(piece + " ")
            piece = word
        else:
            piece = f"{piece} {word}" if piece else word
    pieces.append(piece)
    return "\n".join(["    gettext_noop(", *(f"        {p!r}" for p in pieces), "    ),"])
