"""Read a study's uploaded clips for the admin, and which compared clips do not match."""

from dataclasses import dataclass
from datetime import timedelta
from itertools import combinations

from django.utils import timezone
from django.utils.translation import gettext

from studyplatform.lib.stimuli import needed_pairs
from studyplatform.models import Block, ClipUpload, Stimulus, Study, Trial, UploadedClip

# Clips compared side by side should differ in nothing but the technique: a longer
# clip or a larger picture is a difference participants can see.
MAX_DURATION_RATIO = 1.2


@dataclass(frozen=True)
class UploadCell:
    """One item × uploaded condition: its clip, if uploaded."""

    condition: object
    clip: UploadedClip | None


@dataclass(frozen=True)
class UploadRow:
    """One item and its clips in the study's uploaded conditions."""

    item: object
    cells: tuple[UploadCell, ...]


def uploads_overview(study: Study) -> tuple[list, list[UploadRow]]:
    """Return the study's uploaded conditions and, per item, their uploaded clips.

    The items are those the study's pages show in an uploaded condition; before any
    page shows one, every item.
    """
    conditions = [c for c in study.conditions.all() if c.is_uploaded]
    shown = [item for condition, item in needed_pairs(study) if condition.is_uploaded]
    items = list(dict.fromkeys(shown)) or list(study.items.all())
    clips = {
        (clip.condition_id, clip.item_id): clip
        for clip in UploadedClip.objects.filter(condition__study=study)
    }
    rows = [
        UploadRow(item, tuple(UploadCell(c, clips.get((c.pk, item.pk))) for c in conditions))
        for item in items
    ]
    return conditions, rows


def _compared(study: Study) -> set[tuple[int, int, int]]:
    """Return (item, condition, condition) for every two clips a page shows side by side."""
    every = [c.pk for c in study.conditions.all()]
    pairs = set()
    trials = Trial.objects.filter(study=study, kind__in=Trial.TWO_CLIP_KINDS)
    for trial in trials.select_related("block"):
        if trial.item_id is None or trial.condition_a_id is None:
            continue
        if study.rotate_conditions and trial.block.kind == Block.Kind.TRIALS:
            shown = combinations(every, 2)  # rotation shows the item in every pair
        else:
            shown = [(trial.condition_a_id, trial.condition_b_id)]
        pairs.update((trial.item_id, *sorted(pair)) for pair in shown if pair[0] != pair[1])
    return pairs


def mismatched_pairs(study: Study) -> list[str]:
    """Say, per pair of clips compared on a page, where their length differs by more
    than 20 % or their frame size differs (e.g. an uploaded film beside a rendered clip)."""
    ready = Stimulus.objects.filter(condition__study=study, status=Stimulus.Status.READY)
    clips = {(s.item_id, s.condition_id): s for s in ready.select_related("item", "condition")}
    warnings = []
    for item, first, second in sorted(_compared(study)):
        a, b = clips.get((item, first)), clips.get((item, second))
        if a is None or b is None:
            continue
        where = gettext("%(item)s: %(a)s and %(b)s") % {
            "item": a.item.key,
            "a": a.condition.key,
            "b": b.condition.key,
        }
        if (a.width, a.height) != (b.width, b.height):
            warnings.append(
                gettext("%(where)s differ in frame size (%(a)s and %(b)s).")
                % {"where": where, "a": f"{a.width}×{a.height}", "b": f"{b.width}×{b.height}"}
            )
        shorter, longer = sorted((a.duration_ms or 0, b.duration_ms or 0))
        if shorter and longer / shorter > MAX_DURATION_RATIO:
            warnings.append(
                gettext("%(where)s differ in length by %(percent).0f %% (%(a).2f s and %(b).2f s).")
                % {
                    "where": where,
                    "percent": 100 * (longer / shorter - 1),
                    "a": a.duration_ms / 1000,
                    "b": b.duration_ms / 1000,
                }
            )
    return warnings


def pending_uploads(study: Study) -> list[ClipUpload]:
    """Return the study's clip uploads still converting, and those refused in the last
    day, newest first (the uploads page lists them)."""
    recent = timezone.now() - timedelta(days=1)
    uploads = study.clip_uploads.exclude(status=ClipUpload.Status.DONE)
    return list(uploads.exclude(status=ClipUpload.Status.FAILED, created_at__lt=recent)[:20])
