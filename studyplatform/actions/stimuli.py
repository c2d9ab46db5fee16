"""Generate a study's stimuli: one clip per (condition, item) its trials show.

:func:`do_generate_stimuli` records what to render as :class:`Stimulus` rows keyed by
content hash and sends a Celery job per clip that is not rendered yet, once the
transaction commits. A clip whose hash is unchanged and whose file exists is left
alone, so running it again renders nothing; changing one condition's parameters
re-renders exactly that condition's clips. A clip whose content-addressed files are in
the clips folder already (rendered for another study, version, import or database) is
recorded ready from them, never rendered again.
"""

from dataclasses import dataclass, field

from django.db import transaction
from django.utils import timezone

from stimuli.clips import ClipError, ClipSpec, RenderedClip
from stimuli.clips import rendered as already_rendered
from studyplatform.jobs.background import dispatch_renders
from studyplatform.lib.stimuli import (
    SUBDIRECTORY,
    clip_spec,
    clips_folder,
    describe_identical,
    files_exist,
    group_identical,
    needed_pairs,
)
from studyplatform.models import Stimulus, Study, UploadedClip


@dataclass(frozen=True)
class GenerationResult:
    """How many clips the study needs, how many were queued, how many were ready."""

    total: int
    queued: int
    ready: int
    stimulus_ids: tuple[int, ...]
    missing: int = 0  # clips of uploaded conditions not uploaded yet


class RerenderRefused(ClipError):
    """Generation would silently change clips that participants of an open study have seen."""


class IdenticalClips(ClipError):
    """Two conditions of an item would render the same clip, and nobody confirmed it."""


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


def _in_field(study: Study) -> bool:
    """Return whether the study's clips are in the field: participants of an open (or
    closed) study have seen them."""
    return (
        study.status in (Study.Status.OPEN, Study.Status.CLOSED)
        and study.participants.filter(is_pilot=False).exists()
    )


def _clip_spec(condition, item) -> ClipSpec:
    """Return the specification of one clip; a ClipError names the condition and item."""
    try:
        return clip_spec(condition, item)
    except ClipError as error:
        raise ClipError(f"{condition.key} × {item.key}: {error}") from None


def _record_clip(stimulus: Stimulus, spec: ClipSpec, content_hash: str, force: bool) -> bool:
    """Record one clip as ready (rendered already, here or elsewhere) or pending; return
    whether it must be rendered."""
    unchanged = stimulus.pk and stimulus.content_hash == content_hash
    done = unchanged and stimulus.status == Stimulus.Status.READY and files_exist(stimulus)
    if done and not force:
        return False
    existing = None if force else already_rendered(spec, clips_folder(), content_hash)
    if existing is not None:
        # Rendered already (another study, version, import or database): reuse it.
        _record_ready(stimulus, spec, existing)
        return False
    stimulus.content_hash = content_hash
    stimulus.parameters = spec.to_dict()
    stimulus.engine_version = spec.engine
    stimulus.status = Stimulus.Status.PENDING
    stimulus.error = ""
    stimulus.save()
    return True


@dataclass(frozen=True)
class GenerateOptions:
    """How :func:`do_generate_stimuli` treats a study's clips.

    *force* renders every clip again; *enqueue* False only records them, for a caller
    that renders them itself; *background* renders them in a background process where
    there is no broker (:func:`studyplatform.jobs.background.dispatch_renders`);
    *rerender_open* re-renders clips whose specification changed in a study in the
    field; *allow_identical* accepts two conditions that render an item identically.
    """

    force: bool = False
    enqueue: bool = True
    background: bool = False
    rerender_open: bool = False
    allow_identical: bool = False


@dataclass
class _Tally:
    """What generation found, pair by pair: the clips, those to render, and why not."""

    ids: list[int] = field(default_factory=list)
    queued: list[int] = field(default_factory=list)
    ready: int = 0
    missing: int = 0
    hashed: list[tuple] = field(default_factory=list)  # (condition, item, content hash)
    changed: list[tuple[Stimulus, ClipSpec]] = field(default_factory=list)


def do_generate_stimuli(
    study: Study, options: GenerateOptions = GenerateOptions()
) -> GenerationResult:
    """Record the study's clips and queue the ones not rendered yet (see
    :class:`GenerateOptions`).

    Two conditions that render an item identically raise :class:`IdenticalClips` unless
    allowed: a comparison of identical clips is almost always a forgotten setting. On an
    open or closed study that participants have taken, clips already rendered whose
    specification changed (new parameters, another engine) are re-rendered only with
    *rerender_open*; otherwise :class:`RerenderRefused` names them and nothing changes.
    """
    refuse_changes = _in_field(study) and not options.rerender_open
    tally = _Tally()
    with transaction.atomic(durable=True):
        # Every clip and upload of the study in one query each, not one per pair.
        stimuli = Stimulus.objects.filter(condition__study=study)
        recorded = {(s.condition_id, s.item_id): s for s in stimuli}
        uploads = {
            (u.condition_id, u.item_id): u
            for u in UploadedClip.objects.filter(condition__study=study)
        }
        for condition, item in needed_pairs(study):
            stimulus = recorded.get((condition.pk, item.pk))
            if condition.is_uploaded:
                clip = uploads.get((condition.pk, item.pk))
                stimulus = _record_upload(condition, item, clip, stimulus)
                _tally_upload(tally, condition, item, stimulus)
            else:
                _tally_render(tally, condition, item, stimulus, options.force, refuse_changes)
        identical = group_identical(tally.hashed)
        if identical and not options.allow_identical:
            raise IdenticalClips(describe_identical(identical))
        if tally.changed and refuse_changes:
            _refuse_changes_in_the_field(study, tally.changed)
        queued = tally.queued
        if options.enqueue and queued:
            background = options.background
            transaction.on_commit(lambda: dispatch_renders(queued, background=background))
    return GenerationResult(
        len(tally.ids), len(queued), tally.ready, tuple(tally.ids), tally.missing
    )


def _tally_upload(tally: _Tally, condition, item, stimulus: Stimulus) -> None:
    """Count an uploaded condition's clip: ready from its file, or missing."""
    tally.hashed.append((condition, item, stimulus.content_hash or f"missing-{stimulus.pk}"))
    tally.missing += stimulus.status == Stimulus.Status.MISSING
    tally.ready += stimulus.status == Stimulus.Status.READY
    tally.ids.append(stimulus.pk)


def _tally_render(
    tally: _Tally, condition, item, stimulus: Stimulus | None, force: bool, refuse: bool
) -> None:
    """Record a rendered condition's clip, ready or to render; note a changed one (left
    alone when changes are refused)."""
    spec = _clip_spec(condition, item)
    content_hash = spec.content_hash()
    tally.hashed.append((condition, item, content_hash))
    was_ready = stimulus is not None and stimulus.status == Stimulus.Status.READY
    if was_ready and stimulus.content_hash != content_hash:
        tally.changed.append((stimulus, spec))
        if refuse:
            return
    stimulus = stimulus or Stimulus(condition=condition, item=item)
    if _record_clip(stimulus, spec, content_hash, force):
        tally.queued.append(stimulus.pk)
    else:
        tally.ready += 1
    tally.ids.append(stimulus.pk)


def _record_upload(condition, item, clip: UploadedClip | None, stimulus: Stimulus | None):
    """Record the clip of an uploaded condition: ready from its file, or missing."""
    stimulus = stimulus or Stimulus(condition=condition, item=item)
    if clip is not None:
        return _ready_from_upload(stimulus, clip)
    return _missing(stimulus)


def record_missing_stimulus(condition, item) -> Stimulus:
    """Record that the item's clip in an uploaded condition has no file (yet)."""
    stimulus = Stimulus.objects.filter(condition=condition, item=item).first()
    return _missing(stimulus or Stimulus(condition=condition, item=item))


def _missing(stimulus: Stimulus) -> Stimulus:
    stimulus.status, stimulus.error = Stimulus.Status.MISSING, ""
    stimulus.content_hash = stimulus.sha256 = ""
    stimulus.upload = None
    stimulus.save()
    return stimulus


def record_uploaded_stimulus(clip: UploadedClip) -> Stimulus:
    """Make *clip* the ready clip of its item in its condition; return that stimulus.

    Its content hash is the file's SHA-256: two conditions showing the same file are
    identical clips (the guard of :func:`do_generate_stimuli`).
    """
    stimulus = Stimulus.objects.filter(condition=clip.condition_id, item=clip.item_id).first()
    return _ready_from_upload(stimulus or Stimulus(condition=clip.condition, item=clip.item), clip)


def _ready_from_upload(stimulus: Stimulus, clip: UploadedClip) -> Stimulus:
    stimulus.upload = clip
    stimulus.content_hash = stimulus.sha256 = clip.sha256
    stimulus.parameters = {"source": "uploaded", "file": clip.original_name}
    stimulus.engine_version = ""
    stimulus.video.name = stimulus.poster.name = ""
    for fact in ("duration_ms", "frame_count", "width", "height", "size_bytes"):
        setattr(stimulus, fact, getattr(clip, fact))
    stimulus.status, stimulus.error = Stimulus.Status.READY, ""
    stimulus.rendered_at = clip.uploaded_at or timezone.now()
    stimulus.save()
    return stimulus


def do_retry_stimuli(stimuli, background: bool = False) -> int:
    """Queue failed (or stuck) clips again; return how many (uploaded ones are not
    rendered: they wait for their file)."""
    with transaction.atomic(durable=True):
        pks = [
            s.pk
            for s in stimuli
            if s.status != Stimulus.Status.READY and not s.condition.is_uploaded
        ]
        Stimulus.objects.filter(pk__in=pks).update(status=Stimulus.Status.PENDING, error="")
        if pks:
            transaction.on_commit(lambda: dispatch_renders(pks, background=background))
    return len(pks)


def do_start_rendering(stimulus: Stimulus) -> None:
    """Mark the clip as being rendered."""
    Stimulus.objects.filter(pk=stimulus.pk).update(status=Stimulus.Status.RENDERING)


def do_fail_stimulus(stimulus: Stimulus, error: Exception) -> str:
    """Record why the clip could not be rendered; return its status."""
    Stimulus.objects.filter(pk=stimulus.pk).update(
        status=Stimulus.Status.FAILED, error=f"{type(error).__name__}: {error}"
    )
    return Stimulus.Status.FAILED


def do_record_rendered_stimulus(
    stimulus: Stimulus, spec: ClipSpec, clip: RenderedClip, subdirectory: str
) -> str:
    """Record a rendered clip's files and facts as ready; return the clip's status.

    A clip whose study changed while it rendered (its hash is no longer the row's) is
    not recorded: "superseded".
    """
    with transaction.atomic(durable=True):
        stimulus = Stimulus.objects.select_for_update().get(pk=stimulus.pk)
        if stimulus.content_hash != spec.content_hash():
            return "superseded"
        _record_ready(stimulus, spec, clip, subdirectory)
    return stimulus.status


def _record_ready(
    stimulus: Stimulus, spec: ClipSpec, clip: RenderedClip, subdirectory: str = SUBDIRECTORY
) -> None:
    """Save *stimulus* as ready with *clip*'s files and facts."""
    stimulus.content_hash = spec.content_hash()
    stimulus.parameters = spec.to_dict()
    stimulus.engine_version = spec.engine
    stimulus.video.name = f"{subdirectory}/{clip.video.name}"
    stimulus.poster.name = f"{subdirectory}/{clip.poster.name}"
    stimulus.duration_ms = clip.duration_ms
    stimulus.frame_count = clip.frame_count
    stimulus.width, stimulus.height = clip.width, clip.height
    stimulus.size_bytes = clip.size_bytes
    stimulus.sha256 = clip.sha256
    stimulus.status = Stimulus.Status.READY
    stimulus.error = ""
    stimulus.rendered_at = timezone.now()
    stimulus.save()
