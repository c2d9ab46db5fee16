"""Generate a study's stimuli: one clip per (condition, item) its trials show.

:func:`do_generate_stimuli` records what to render as :class:`Stimulus` rows keyed by
content hash and sends a Celery job per clip that is not rendered yet, once the
transaction commits. A clip whose hash is unchanged and whose file exists is left
alone, so running it again renders nothing; changing one condition's parameters
re-renders exactly that condition's clips.
"""

import zlib
from dataclasses import dataclass
from pathlib import Path

from django.db import transaction

from stimuli.clips import ClipError, ClipSpec, RenderedClip
from stimuli.manifest import Entry
from studyplatform.models import Block, Condition, Item, Stimulus, Study, Trial
from synthesis.techniques import ClipRequest


@dataclass(frozen=True)
class GenerationResult:
    """How many clips the study needs, how many were queued, how many were ready."""

    total: int
    queued: int
    ready: int
    stimulus_ids: tuple[int, ...]


def clip_spec(condition: Condition, item: Item) -> ClipSpec:
    """Return the clip specification of *condition* applied to *item*.

    The condition's parameters override the item's. The seed is the item's (its
    parameters' ``seed``, else a checksum of its key), so all conditions of an item share
    one performance and one noise.
    """
    parameters = {**(item.parameters or {}), **(condition.parameters or {})}
    parameters.setdefault("seed", zlib.crc32(item.key.encode()))
    return ClipSpec.from_request(ClipRequest.from_parameters(item.kind, item.text, parameters))


def needed_pairs(study: Study) -> list[tuple[Condition, Item]]:
    """Return the (condition, item) pairs the study's trials show, in design order.

    Under Latin-square rotation a trial block's item is shown in every condition.
    """
    pairs = []
    trials = Trial.objects.filter(block__study=study).select_related(
        "block", "item", "condition_a", "condition_b"
    )
    every_condition = list(study.conditions.all())
    for trial in trials:
        shown = [trial.condition_a, trial.condition_b]
        rotated = study.rotate_conditions and trial.block.kind == Block.Kind.TRIALS
        if rotated and trial.condition_a is not None:
            shown = every_condition  # participants' rows relabel the conditions
        for condition in shown:
            if trial.item is not None and condition is not None:
                pair = (condition, trial.item)
                if pair not in pairs:
                    pairs.append(pair)
    return sorted(pairs, key=lambda p: (p[1].position, p[0].position))


class RerenderRefused(ClipError):
    """Generation would silently change clips that participants of an open study have seen."""


def _refuse_changes_in_the_field(study: Study, changed: list[tuple[Stimulus, ClipSpec]]) -> None:
    engines = sorted({stimulus.engine_version for stimulus, _ in changed})
    current = changed[0][1].engine
    raise RerenderRefused(
        f"“{study.title}” is {study.get_status_display().lower()}: {len(changed)} of its "
        f"rendered clips would change (rendered by engine {', '.join(engines)}; this "
        f"installation's engine is {current}), so participants would see other clips than "
        "those already shown. Render with the engine the clips were made with (a checkout "
        "whose 'python -m synthesis version' prints it), or re-render on purpose "
        "(generate_stimuli --rerender-open)."
    )


def do_generate_stimuli(
    study: Study, force: bool = False, enqueue: bool = True, rerender_open: bool = False
) -> GenerationResult:
    """Record the study's clips and queue the ones not rendered yet (all with *force*).

    *enqueue* False only records them, for a caller that renders them itself. On an open
    or closed study that participants have taken, clips already rendered whose
    specification changed (new parameters, another engine) are re-rendered only with
    *rerender_open*; otherwise :class:`RerenderRefused` names them and nothing changes.
    """
    from studyplatform.tasks import render_stimulus

    queued, ready, ids, changed = [], 0, [], []
    # Clips are in the field once participants of an open (or closed) study have seen them.
    in_field = (
        study.status in (Study.Status.OPEN, Study.Status.CLOSED)
        and study.participants.filter(is_pilot=False).exists()
    )
    with transaction.atomic():
        for condition, item in needed_pairs(study):
            try:
                spec = clip_spec(condition, item)
            except ClipError as error:
                raise ClipError(f"{condition.key} × {item.key}: {error}") from None
            content_hash = spec.content_hash()
            stimulus = Stimulus.objects.filter(condition=condition, item=item).first()
            rendered = stimulus is not None and stimulus.status == Stimulus.Status.READY
            if rendered and stimulus.content_hash != content_hash:
                changed.append((stimulus, spec))
                if in_field and not rerender_open:
                    continue
            if stimulus is None:
                stimulus = Stimulus(condition=condition, item=item)
            unchanged = stimulus.pk and stimulus.content_hash == content_hash
            done = unchanged and stimulus.status == Stimulus.Status.READY and _files_exist(stimulus)
            if done and not force:
                ready += 1
            else:
                stimulus.content_hash = content_hash
                stimulus.parameters = spec.to_dict()
                stimulus.engine_version = spec.engine
                stimulus.status = Stimulus.Status.PENDING
                stimulus.error = ""
                stimulus.save()
                queued.append(stimulus.pk)
            ids.append(stimulus.pk)
        if changed and in_field and not rerender_open:
            _refuse_changes_in_the_field(study, changed)
        for pk in queued if enqueue else ():
            transaction.on_commit(lambda pk=pk: render_stimulus.delay(pk))
    return GenerationResult(len(ids), len(queued), ready, tuple(ids))


def do_retry_stimuli(stimuli) -> int:
    """Queue failed (or stuck) clips again; return how many."""
    from studyplatform.tasks import render_stimulus

    with transaction.atomic():
        pks = [s.pk for s in stimuli if s.status != Stimulus.Status.READY]
        Stimulus.objects.filter(pk__in=pks).update(status=Stimulus.Status.PENDING, error="")
        for pk in pks:
            transaction.on_commit(lambda pk=pk: render_stimulus.delay(pk))
    return len(pks)


def _files_exist(stimulus: Stimulus) -> bool:
    return bool(stimulus.video) and stimulus.video.storage.exists(stimulus.video.name)


def stimuli_progress(study: Study) -> dict:
    """Return the study's clips by status, with each failure's error (for the admin)."""
    stimuli = Stimulus.objects.filter(condition__study=study).select_related("condition", "item")
    counts = {status: 0 for status in Stimulus.Status.values}
    failures = []
    for stimulus in stimuli:
        counts[stimulus.status] += 1
        if stimulus.status == Stimulus.Status.FAILED:
            failures.append({"id": stimulus.pk, "clip": str(stimulus), "error": stimulus.error})
    total = sum(counts.values())
    done = counts[Stimulus.Status.READY]
    return {
        "total": total,
        "done": done,
        "failed": counts[Stimulus.Status.FAILED],
        "pending": counts[Stimulus.Status.PENDING] + counts[Stimulus.Status.RENDERING],
        "percent": round(100 * done / total) if total else 0,
        "failures": failures,
    }


def study_manifest(study: Study) -> list[Entry]:
    """Return the manifest entries of the study's clips: every rendered clip's spec and facts.

    Clips not rendered yet appear with their spec only, so the manifest still renders them.
    """
    entries = []
    stimuli = Stimulus.objects.filter(condition__study=study).select_related("condition", "item")
    for stimulus in stimuli.order_by("item__position", "condition__position", "pk"):
        clip = None
        if stimulus.status == Stimulus.Status.READY and stimulus.video:
            clip = RenderedClip(
                Path(stimulus.video.name).relative_to("stimuli"),
                Path(stimulus.poster.name).relative_to("stimuli"),
                stimulus.duration_ms, stimulus.frame_count, stimulus.width, stimulus.height,
                stimulus.size_bytes, stimulus.sha256,
            )  # fmt: skip
        label = f"{stimulus.condition.key} × {stimulus.item.key}"
        entries.append(Entry(label, ClipSpec.from_dict(stimulus.parameters), clip))
    return entries
