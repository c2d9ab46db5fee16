"""Receive signed answers recorded with the webcam, in chunks that survive a lost connection.

The browser sends the recording in chunks, each saying at which byte it starts. A chunk
that does not start where the stored part ends is refused with the stored length, so
the browser resumes from there after a dropped connection, and a repeated chunk is
never appended twice; a chunk at byte 0 starts a new recording. The last chunk turns
the part into the answer's video file.

Unfinished parts and finished answers live in private storage
(``SIGNSTUDY_PRIVATE_MEDIA_ROOT``, :mod:`studyplatform.storage`); no public URL
reaches them. A part nobody has added to for ``SIGNSTUDY_PARTIAL_UPLOAD_MAX_AGE_HOURS``
was abandoned, and :func:`do_remove_abandoned_uploads` deletes it.
"""

import os
import secrets
import time
from pathlib import Path

from django.conf import settings
from django.core.exceptions import ValidationError
from django.core.files import File
from django.db import transaction

from studyplatform.actions.media import delete_unused_files_on_commit
from studyplatform.lib.video_check import container_suffix, decodes_as_video
from studyplatform.models import Participant, Question, Response, Trial

MAX_SIGNED_ANSWER_BYTES = 200 * 1024 * 1024


class UploadRejected(ValidationError):
    """A chunk or recording that cannot be taken; what was stored before is kept."""


class UploadOffsetMismatch(UploadRejected):
    """A chunk that does not start where the stored part ends; resume from *offset*."""

    def __init__(self, offset: int):
        super().__init__(f"The upload continues at byte {offset}.")
        self.offset = offset


def partial_path(participant: Participant, trial: Trial, question: Question) -> Path:
    """Return where the unfinished upload of this answer is kept."""
    name = f"{participant.pk}-{trial.pk}-{question.pk}.part"
    return partial_directory() / name


def partial_directory() -> Path:
    """Return the directory of unfinished uploads (private, never served)."""
    return Path(settings.SIGNSTUDY_PRIVATE_MEDIA_ROOT) / "answers" / "partial"


def upload_offset(participant: Participant, trial: Trial, question: Question) -> int:
    """Return how many bytes of this answer's recording are stored so far."""
    path = partial_path(participant, trial, question)
    return path.stat().st_size if path.exists() else 0


def _check_question(trial: Trial, question: Question) -> None:
    if not question.allow_signed_answer:
        raise UploadRejected(f"“{question.key}” does not take a signed answer.")
    if question.pk not in {asked.pk for asked in trial.questions.all()}:  # prefetched or one query
        raise UploadRejected(f"“{question.key}” is not asked on this page.")


def do_append_signed_answer_chunk(
    participant: Participant,
    trial: Trial,
    question: Question,
    offset: int,
    chunk: bytes,
    final: bool,
) -> tuple[int, Response | None]:
    """Append *chunk* at byte *offset*; with *final*, save the recording as the answer.

    Return the stored length and, after the final chunk, the saved Response.
    """
    if participant.is_finished:
        raise UploadRejected("This study is finished; answers can no longer change.")
    _check_question(trial, question)
    with transaction.atomic():
        # One writer per participant at a time: concurrent chunks cannot interleave.
        Participant.objects.select_for_update().get(pk=participant.pk)
        path = partial_path(participant, trial, question)
        if offset == 0:
            path.unlink(missing_ok=True)  # a new recording starts over
        stored = upload_offset(participant, trial, question)
        if offset != stored:
            raise UploadOffsetMismatch(stored)
        if stored + len(chunk) > MAX_SIGNED_ANSWER_BYTES:
            path.unlink(missing_ok=True)
            limit = MAX_SIGNED_ANSWER_BYTES // (1024 * 1024)
            raise UploadRejected(f"The recording is longer than {limit} MB allows.")
        path.parent.mkdir(parents=True, exist_ok=True)
        with open(path, "ab") as part:
            part.write(chunk)
            part.flush()
            os.fsync(part.fileno())
        stored += len(chunk)
    if not final:
        return stored, None
    # Decoding takes a moment: outside the lock, so other participants' saves don't wait
    # on SQLite's single writer. A final chunk sent again after a failure here finds the
    # whole part stored (409 with its length) and sends an empty final chunk.
    suffix = container_suffix(path)
    if suffix is None or not decodes_as_video(path):
        path.unlink(missing_ok=True)
        raise UploadRejected("The recording is not a WebM or MP4 video.")
    return stored, _save_recording(participant, trial, question, path, stored, suffix)


def _save_recording(participant: Participant, trial: Trial, question: Question, path: Path,
                    length: int, suffix: str) -> Response:  # fmt: skip
    """Save the checked part at *path* as the answer's video (replacing an older one)."""
    with transaction.atomic():
        Participant.objects.select_for_update().get(pk=participant.pk)
        stored = upload_offset(participant, trial, question)
        if stored != length:  # a new recording started meanwhile
            raise UploadOffsetMismatch(stored)
        response = Response.objects.select_for_update().filter(
            participant=participant, trial=trial, question=question
        ).first() or Response(participant=participant, trial=trial, question=question)
        old = response.video.name if response.video else ""
        # 128 random bits: the name alone never lets anyone guess another answer's file.
        name = f"{participant.pk}-{trial.key}-{question.key}-{secrets.token_hex(16)}{suffix}"
        with open(path, "rb") as part:
            response.video.save(name, File(part), save=False)
        if response.pk:
            response.revision += 1
        response.save()
        path.unlink(missing_ok=True)
        delete_unused_files_on_commit(response.video.storage, [old])
    return response


def do_remove_abandoned_uploads(max_age_hours: float) -> list[str]:
    """Delete unfinished uploads not added to for *max_age_hours*; return their names.

    A participant who comes back later starts that recording again (the page asks the
    server where to resume, and an absent part resumes at byte 0).
    """
    if max_age_hours <= 0:
        raise ValueError(f"The maximum age must be positive; {max_age_hours} hours is not.")
    cutoff = time.time() - max_age_hours * 3600
    removed = []
    directory = partial_directory()
    for path in sorted(directory.glob("*.part")) if directory.is_dir() else ():
        try:
            if path.stat().st_mtime < cutoff:
                path.unlink()
                removed.append(path.name)
        except FileNotFoundError:  # finished or removed meanwhile
            continue
    return removed
