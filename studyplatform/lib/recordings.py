"""Read which recording an item's clips are made from, and which conditions it replaces.

An item's performance is its newest ready recording. Which conditions take it, and how,
is the source technique's rule (:mod:`synthesis.techniques.source`, seed 000 §4.3).
"""

from collections.abc import Mapping
from pathlib import Path
from typing import Any

from studyplatform.models import Condition, Item, Recording, Study
from synthesis.techniques import (
    is_simulated_stand_in,
    retimes_recording,
    takes_item_recording,
    uses_item_recording,
    with_recording,
)


def current_recording(item: Item) -> Recording | None:
    """Return the item's newest ready recording, or None."""
    ready = item.recordings.filter(status=Recording.Status.READY).exclude(motion="")
    return ready.order_by("-created_at", "-pk").first()


def with_item_recording(parameters: Mapping[str, Any], item: Item, condition_key: str) -> dict:
    """Return a word's clip *parameters* with its recording as the performance.

    Conditions that take a word's own recording take the item's newest ready one; a
    simulated capture stays where there is none. Raise ClipError when a condition
    retimes each word's recording and this word has none.
    """
    from stimuli.clips import ClipError

    parameters = dict(parameters)
    if item.kind != Item.Kind.WORD or not takes_item_recording(parameters):
        return parameters
    recording = current_recording(item)
    if recording is not None:
        parameters = with_recording(parameters, str(Path(recording.motion.path)))
    elif uses_item_recording(parameters):
        raise ClipError(
            f"{item.key} has no recording yet, and condition {condition_key!r} retimes "
            "each word's recording: upload one on the item's Recordings, or wait for "
            "its capture to finish."
        )
    return parameters


def words_without_recording(study: Study) -> list[Item]:
    """Return the study's words that have no ready recording, in design order."""
    ready = Recording.objects.filter(item__study=study, status=Recording.Status.READY)
    recorded = set(ready.exclude(motion="").values_list("item_id", flat=True))
    words = study.items.filter(kind=Item.Kind.WORD)
    return [item for item in words if item.pk not in recorded]


def stand_in_conditions(study: Study) -> list[Condition]:
    """Return the study's conditions that stand in for motion capture."""
    return [c for c in study.conditions.all() if is_simulated_stand_in(c.parameters or {})]


def recordings_overview(study: Study) -> dict:
    """Return each word of the study with the recording in use and the newest attempt.

    For the admin's Recordings page and its progress poll: ``words`` lists per word its
    key, text, the ready recording's quality and the newest upload's status, progress
    and error; ``capturing`` counts uploads still being captured.
    """
    words = []
    recordings = Recording.objects.filter(item__study=study).order_by("-created_at", "-pk")
    newest: dict[int, Recording] = {}
    ready: dict[int, Recording] = {}
    for recording in recordings:
        newest.setdefault(recording.item_id, recording)
        if recording.status == Recording.Status.READY:
            ready.setdefault(recording.item_id, recording)
    for item in study.items.filter(kind=Item.Kind.WORD):
        latest, used = newest.get(item.pk), ready.get(item.pk)
        words.append(
            {
                "item": item.pk,
                "key": item.key,
                "text": item.text,
                "used": _describe(used),
                "latest": _describe(latest) if latest is not None and latest != used else None,
            }
        )
    capturing = sum(1 for r in newest.values() if r.status == Recording.Status.CAPTURING)
    return {
        "words": words,
        "recorded": sum(1 for word in words if word["used"]),
        "capturing": capturing,
    }


def _describe(recording: Recording | None) -> dict | None:
    if recording is None:
        return None
    quality = recording.quality or {}
    found = quality.get("hands_found") or {}
    return {
        "id": recording.pk,
        "file": recording.upload.name.rsplit("/", 1)[-1],
        "url": recording.upload.url,
        "sheet_url": recording.sheet.url if recording.sheet else None,
        "status": recording.status,
        "status_label": recording.get_status_display(),
        "percent": recording.progress_percent,
        "error": recording.error,
        "frames": quality.get("frames"),
        "hand_found_percent": round(100 * max(found.values())) if found else None,
        "residual_mm": quality.get("residual_mm_median"),
        "warnings": quality.get("warnings") or [],
    }


def retimes_recordings(study: Study) -> bool:
    """Return whether a condition of the study retimes its words' recordings (so their
    holds must be found), rather than only playing them as performed."""
    return any(retimes_recording(c.parameters or {}) for c in study.conditions.all())
