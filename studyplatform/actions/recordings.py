"""Attach recordings to a study's words and turn them into the motion clips retime.

:func:`do_attach_recording` stores an upload and queues its preparation (a Celery job
sent on commit): a video is captured with MediaPipe into a ``.pose`` file, and every
recording is fitted and its holds extracted before it is marked ready. Until then the
item's older recording (or the simulated stand-in) stays in use.
"""

import hashlib

from django.core.exceptions import ValidationError
from django.core.files import File
from django.core.files.base import ContentFile
from django.db import transaction

from studyplatform.actions.media import delete_unused_files_on_commit
from studyplatform.confine import ConfinedError, run_task
from studyplatform.files.media_types import (
    MediaKind,
    MediaRejected,
    check_upload,
    stored_video,
)
from studyplatform.files.storage import PRIVATE_STORAGE
from studyplatform.jobs.queue import PREPARE_RECORDING, queue_job_on_commit
from studyplatform.lib.recordings import stand_in_conditions, words_without_recording
from studyplatform.models import Item, Recording, Study

MAX_RECORDING_BYTES = 300 * 1024 * 1024


class RecordingRejected(ValidationError):
    """An upload that cannot be a recording of the item; nothing was stored."""


def check_motion_file(name: str, data: bytes, kind: MediaKind) -> dict:
    """Return what a .pose, BVH, FBX or glTF file (by content: *kind*) holds as motion
    (frames, rate, and for FBX and glTF the motion as BVH), read confined
    (:mod:`studyplatform.confine`); RecordingRejected names what is wrong, or the limit
    the file hit."""
    try:
        return run_task("motion", data, f"“{name}”", kind.suffix)
    except ConfinedError as error:
        raise RecordingRejected(str(error)) from None


def do_attach_recording(
    item: Item, upload, mirrored: bool = False, one_hand: bool = False
) -> Recording:
    """Store *upload* as a recording of *item* and queue its preparation.

    Raise RecordingRejected for an item that is not a word, a file that is neither a
    video nor a .pose or BVH file (by content, whatever its name), one over 300 MB, a
    video that does not decode, or a .pose or BVH file that does not parse; nothing is
    stored then.
    """
    name = getattr(upload, "name", "") or ""
    if item.kind != Item.Kind.WORD:
        raise RecordingRejected(
            f"{item.key} is a {item.get_kind_display().lower()}: only fingerspelled words "
            "take recordings."
        )
    if upload.size > MAX_RECORDING_BYTES:
        raise RecordingRejected("The recording is larger than 300 MB.")
    try:
        kind = check_upload(upload, ("video", "motion", "model"), f"“{name}”")
    except MediaRejected:
        raise RecordingRejected(
            f"“{name}” is not a recording: upload a video (MP4, WebM, MOV), a .pose file, "
            "a BVH, FBX or glTF (GLB) motion (judged by its content)."
        ) from None
    if kind.family in ("motion", "model"):
        upload.seek(0)
        check_motion_file(name, upload.read(), kind)
        digest = hashlib.sha256()
        for chunk in upload.chunks():
            digest.update(chunk)
        upload.seek(0)
        return _save_recording(item, upload, name, digest.hexdigest(), mirrored, one_hand)
    # A camera's WebM is stored with its duration and seek index, named by its content.
    with stored_video(upload, kind) as (stored, sha256):
        return _save_recording(
            item, File(stored), f"{sha256}{kind.suffix}", sha256, mirrored, one_hand
        )


def _save_recording(
    item: Item, upload, name: str, sha256: str, mirrored: bool, one_hand: bool
) -> Recording:
    with transaction.atomic():
        recording = Recording(item=item, mirrored=mirrored, one_hand=one_hand, sha256=sha256)
        recording.upload.save(name, upload, save=False)
        recording.save()
        queue_job_on_commit(PREPARE_RECORDING, recording.pk)
    return recording


def do_report_capture_progress(recording: Recording, percent: int) -> None:
    """Record how far the recording's capture has come (0–100)."""
    Recording.objects.filter(pk=recording.pk, status=Recording.Status.CAPTURING).update(
        progress_percent=max(0, min(100, int(percent)))
    )


def do_fail_recording(recording: Recording, error: Exception) -> str:
    """Record why the recording cannot be used; return its status.

    The engine names the file it read by its path; the researcher sees it by its name in
    media, not where the server keeps it.
    """
    message = str(error).replace(str(PRIVATE_STORAGE.location).rstrip("/") + "/", "")
    Recording.objects.filter(pk=recording.pk).update(status=Recording.Status.FAILED, error=message)
    return Recording.Status.FAILED


def do_finish_recording(
    recording: Recording,
    quality: dict,
    pose: bytes | None = None,
    sheet: bytes | None = None,
    bvh: bytes | None = None,
) -> str:
    """Mark the recording ready, with its captured landmarks (*pose*) and contact sheet
    (*sheet*, PNG) for a video, or an FBX's or glTF's motion as BVH (*bvh*).

    Older recordings of the item are removed with their files, and the study's stand-in
    conditions are relabelled (:func:`relabel_stand_ins`).
    """
    with transaction.atomic(durable=True):
        recording = Recording.objects.select_for_update().get(pk=recording.pk)
        stem = recording.upload.name.rsplit("/", 1)[-1].rsplit(".", 1)[0]
        if pose is not None:
            recording.motion.save(f"{stem}.pose", ContentFile(pose), save=False)
        elif bvh is not None:
            recording.motion.save(f"{stem}.bvh", ContentFile(bvh), save=False)
        else:
            recording.motion.name = recording.upload.name
        if sheet is not None:
            recording.sheet.save(f"{stem}-contact.png", ContentFile(sheet), save=False)
        recording.status = Recording.Status.READY
        recording.progress_percent = 100
        recording.quality = quality
        recording.error = ""
        recording.save()
        _remove(Recording.objects.filter(item_id=recording.item_id).exclude(pk=recording.pk))
        relabel_stand_ins(recording.item.study)
    return recording.status


def do_delete_recordings(recordings) -> int:
    """Delete recordings with their files and relabel their studies; return how many."""
    with transaction.atomic(durable=True):
        recordings = list(
            Recording.objects.select_for_update()
            .filter(pk__in=[r.pk for r in recordings])
            .select_related("item__study")
        )
        _remove(recordings)
        for study in {r.item.study for r in recordings}:
            relabel_stand_ins(study)
    return len(recordings)


def _remove(recordings) -> None:
    """Delete *recordings*' rows now and their files once the transaction commits, but
    not files another recording still uses (a duplicated study shares its files)."""
    recordings = list(recordings)
    files = {f.name for r in recordings for f in (r.upload, r.motion, r.sheet) if f}
    Recording.objects.filter(pk__in=[r.pk for r in recordings]).delete()
    delete_unused_files_on_commit(Recording._meta.get_field("upload").storage, files)


def relabel_stand_ins(study: Study) -> int:
    """Label the study's motion-capture stand-ins simulated exactly while a word lacks a
    recording; return how many conditions changed.

    Part of the caller's transaction: the actions that add or remove a recording, or
    import a study, relabel in the same commit.
    """
    simulated = bool(words_without_recording(study))
    changed = 0
    for condition in stand_in_conditions(study):
        if condition.is_simulated != simulated:
            condition.is_simulated = simulated
            condition.save(update_fields=["is_simulated"])
            changed += 1
    return changed
