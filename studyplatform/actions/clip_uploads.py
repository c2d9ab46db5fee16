"""Take researchers' clip uploads at once and make them playable in the background.

The request checks what needs no decoding (:func:`check_clip`, :func:`check_clips_zip`)
and keeps the file under ``incoming/`` with a :class:`ClipUpload`; the job decodes,
converts and stores (:func:`do_upload_clip`, :func:`do_import_clips`, all or nothing),
reporting each clip, so no web request waits for ffmpeg (issue 51).
"""

import uuid
from datetime import timedelta
from pathlib import Path

from django.conf import settings
from django.core.files import File
from django.db import transaction
from django.utils import timezone

from studyplatform.actions.clips import (
    ClipUploadRejected,
    check_clip,
    check_clips_zip,
    do_import_clips,
    do_upload_clip,
)
from studyplatform.files.video_files import copy_upload
from studyplatform.jobs.queue import PREPARE_CLIPS, queue_job_on_commit
from studyplatform.models import ClipUpload, Condition, Item, Study

CONVERTED = {
    "remuxed": " (rewrapped for browsers)",
    "transcoded": " (converted to H.264 for browsers)",
}


def incoming_directory() -> Path:
    """Return where uploads wait for their conversion (private, never served)."""
    return Path(settings.SIGNSTUDY_PRIVATE_MEDIA_ROOT) / "incoming"


def _keep(study: Study, upload, total: int, **target) -> ClipUpload:
    folder = incoming_directory()
    folder.mkdir(parents=True, exist_ok=True)
    incoming = uuid.uuid4().hex
    copy_upload(upload, folder / incoming)
    name = (getattr(upload, "name", "") or "upload")[:255]
    with transaction.atomic():
        job = ClipUpload.objects.create(
            study=study, incoming=incoming, original_name=name, total=total, **target
        )
        queue_job_on_commit(PREPARE_CLIPS, job.pk)
    return job


def do_queue_clip(condition: Condition, item: Item, upload) -> ClipUpload:
    """Keep a video for *item* in *condition* and queue its conversion; ClipUploadRejected
    names what :func:`check_clip` finds wrong at once."""
    check_clip(condition, item, upload)
    return _keep(condition.study, upload, 1, condition=condition, item=item)


def do_queue_clips_zip(study: Study, upload) -> ClipUpload:
    """Keep a zip of clips with its manifest and queue their conversion; ClipUploadRejected
    names what :func:`check_clips_zip` finds wrong at once."""
    total = check_clips_zip(study, upload)
    return _keep(study, upload, total)


def _report(job: ClipUpload, done: int) -> None:
    ClipUpload.objects.filter(pk=job.pk).update(done=done)


def do_prepare_clip_upload(job: ClipUpload) -> str:
    """Convert and store the clips of *job*; record what was saved or why nothing was,
    delete the kept file, and return the job's status."""
    ClipUpload.objects.filter(pk=job.pk).update(status=ClipUpload.Status.CONVERTING)
    path = incoming_directory() / job.incoming
    try:
        with open(path, "rb") as handle:
            kept = File(handle, name=job.original_name)
            if job.is_zip:
                clips = do_import_clips(job.study, kept, progress=lambda n: _report(job, n))
                plural = "" if len(clips) == 1 else "s"
                message = f"{len(clips)} clip{plural} uploaded from {job.original_name}."
            else:
                clip = do_upload_clip(job.condition, job.item, kept)
                message = (
                    f"Clip of {job.item.key} in {job.condition.key} saved"
                    f"{CONVERTED.get(clip.converted, '')}: {clip.width}×{clip.height}, "
                    f"{clip.duration_ms / 1000:.2f} s, {clip.frame_rate:g} fps."
                )
        status, done = ClipUpload.Status.DONE, job.total
    except ClipUploadRejected as error:
        message, status, done = error.messages[0], ClipUpload.Status.FAILED, 0
    except FileNotFoundError:  # a second run of the job after the first finished
        message = "The upload was lost before it was converted; upload it again."
        status, done = ClipUpload.Status.FAILED, 0
    finally:
        path.unlink(missing_ok=True)
    ClipUpload.objects.filter(pk=job.pk).update(status=status, done=done, message=message)
    return status


def do_fail_stale_clip_uploads(max_age_hours: float) -> int:
    """Mark uploads queued or converting for longer than *max_age_hours* as failed and
    delete their kept files (a job lost with its broker or worker); return how many."""
    old = timezone.now() - timedelta(hours=max_age_hours)
    waiting = (ClipUpload.Status.QUEUED, ClipUpload.Status.CONVERTING)
    stale = list(ClipUpload.objects.filter(status__in=waiting, created_at__lt=old))
    for job in stale:
        (incoming_directory() / job.incoming).unlink(missing_ok=True)
    ClipUpload.objects.filter(pk__in=[job.pk for job in stale]).update(
        status=ClipUpload.Status.FAILED,
        message="It was not converted in time (the job was lost); upload it again.",
    )
    return len(stale)
