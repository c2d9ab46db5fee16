"""Pieces shared by the demo study definitions."""

from typing import Any

from studyplatform.lib import exchange
from studyplatform.models.studies import CLIP_SIZE


def definition(study: dict[str, Any], **parts: list[dict[str, Any]]) -> dict[str, Any]:
    """Wrap the parts of a study in the exchange format's envelope, filmed at a new
    study's clip size (HD: issue 52)."""
    return {
        "format": exchange.FORMAT,
        "version": exchange.VERSION,
        "study": {"clip_width": CLIP_SIZE[0], "clip_height": CLIP_SIZE[1], **study},
        "conditions": parts.get("conditions", []),
        "items": parts.get("items", []),
        "questions": parts.get("questions", []),
        "blocks": parts.get("blocks", []),
        "trials": parts.get("trials", []),
        "asl_videos": [],
    }


def numbered(rows: list[dict[str, Any]]) -> list[dict[str, Any]]:
    """Give each row its position in the list."""
    return [{**row, "position": index} for index, row in enumerate(rows)]


def scale(labels: list[str]) -> list[dict[str, Any]]:
    """Return answer options valued 1..n with the given labels."""
    return numbered([{"value": value, "label": label} for value, label in enumerate(labels, 1)])


def likert5(low: str, high: str) -> list[dict[str, Any]]:
    """Return a 5-point scale labelled only at its ends (seed 003 Table 2)."""
    return scale([low, "", "", "", high])


# Seed 000 §5.2's ASL skill levels (spec 02 "Before"): every demo asks this one scale, so
# their data can be pooled and filtered alike.
ASL_FLUENCY = (
    "Completely fluent (native or primary language)",
    "Completely fluent (ASL expert)",
    "Somewhat fluent (studied ASL)",
    "Know some ASL, but not fluent",
    "Do not know ASL",
)


def asl_fluency() -> dict[str, Any]:
    """Return the demographic question on ASL fluency (seed 000 §5.2's five levels)."""
    return {
        "key": "asl-fluency",
        "kind": "choice",
        "text": "How fluent are you in ASL?",
        "options": scale(list(ASL_FLUENCY)),
    }


def about_you() -> tuple[dict[str, Any], dict[str, Any]]:
    """Return the "About you" block and its page, which asks :func:`asl_fluency`."""
    block = {"key": "about-you", "kind": "demographics", "title": "About you"}
    page = {
        "key": "about-you",
        "block": "about-you",
        "kind": "demographic",
        "questions": ["asl-fluency"],
    }
    return block, page
