"""Receive signed answers recorded with the webcam, in chunks that survive a lost connection.

Each recording the participant makes (a *take*) has an id the browser creates, a UUID,
sent with every chunk and every question of where to resume. The browser sends a take in
chunks, each saying at which byte it starts. A chunk that does not start where that
take's stored part ends is refused with the stored length, so the browser resumes from
there after a dropped connection, and a repeated chunk is never appended twice; a chunk
at byte 0 starts the take afresh and discards every other take's part of the answer. A
take's bytes are never joined to another's (issue 33: resuming by offset alone spliced a
discarded take's head onto the saved answer). The last chunk says the whole file's
SHA-256 and, optionally, its length in time; the part becomes the answer's video only if
it matches them and decodes to its end.

Unfinished parts and finished answers live in private storage
(``SIGNSTUDY_PRIVATE_MEDIA_ROOT``, :mod:`studyplatform.files.storage`); no public URL
reaches them. A part nobody has added to for ``SIGNSTUDY_PARTIAL_UPLOAD_MAX_AGE_HOURS``
was abandoned, and :func:`do_remove_abandoned_uploads` deletes it.
"""

import hashlib
import math
import os
import secrets
import tempfile
import time
import uuid
from dataclasses import dataclass
from pathlib import Path

from django.conf import settings
from django.core.exceptions import ValidationError
from django.core.files import File
from django.db import transaction
from django.utils.translation import gettext

from stimuli.clips import file_sha256
from studyplatform.actions.media import delete_unused_files_on_commit
from studyplatform.files.media_types import decoded_duration_s, remux_webm, sniff
from studyplatform.models import Participant, Question, Response, Trial

MAX_SIGNED_ANSWER_BYTES = 200 * 1024 * 1024
# How far the decoded length may be from the one the browser measured between starting
# and stopping the recorder: a busy machine's camera sends its first frame late, so the
# check catches another recording, not a slow start.
DURATION_TOLERANCE_S = 2.0
DURATION_TOLERANCE_SHARE = 0.5


class UploadRejected(ValidationError):
    """A chunk or recording that cannot be taken; what was stored before is kept."""


class UploadOffsetMismatch(UploadRejected):
    """A chunk that does not start where the stored part ends; resume from *offset*."""

    def __init__(self, offset: int):
        super().__init__(f"The upload continues at byte {offset}.")
        self.offset = offset


@dataclass(frozen=True)
class FinalChunk:
    """What the browser says of the whole take with its last chunk."""

    sha256: str
    duration_ms: float | None = None


def take_id(value: object) -> str:
    """Return the take id *value* (a UUID) in its canonical form; UploadRejected if it is none."""
    try:
        return str(uuid.UUID(str(value)))
    except ValueError:
        raise UploadRejected("The recording does not say which take it is.") from None


def partial_path(participant: Participant, trial: Trial, question: Question, take: str) -> Path:
    """Return where the unfinished upload of this take of the answer is kept."""
    return partial_directory() / f"{_answer_prefix(participant, trial, question)}{take}.part"


def _answer_prefix(participant: Participant, trial: Trial, question: Question) -> str:
    return f"{participant.pk}-{trial.pk}-{question.pk}-"


def partial_directory() -> Path:
    """Return the directory of unfinished uploads (private, never served)."""
    return Path(settings.SIGNSTUDY_PRIVATE_MEDIA_ROOT) / "answers" / "partial"


def upload_offset(participant: Participant, trial: Trial, question: Question, take: str) -> int:
    """Return how many bytes of this take of the answer are stored so far."""
    path = partial_path(participant, trial, question, take)
    return path.stat().st_size if path.exists() else 0


def _discard_takes(participant: Participant, trial: Trial, question: Question) -> None:
    """Delete every unfinished take of this answer."""
    for path in partial_directory().glob(f"{_answer_prefix(participant, trial, question)}*.part"):
        path.unlink(missing_ok=True)


def partial_uploads(participant_pk: int) -> list[Path]:
    """Return the unfinished uploads of the participant numbered *participant_pk*."""
    directory = partial_directory()
    return sorted(directory.glob(f"{participant_pk}-*.part")) if directory.is_dir() else []


def discard_partial_uploads(participant_pk: int) -> None:
    """Delete every unfinished upload of the participant numbered *participant_pk*."""
    for path in partial_uploads(participant_pk):
        path.unlink(missing_ok=True)


def _check_question(trial: Trial, question: Question) -> None:
    if not question.allow_signed_answer:
        raise UploadRejected(f"“{question.key}” does not take a signed answer.")
    if question.pk not in {asked.pk for asked in trial.questions.all()}:  # prefetched or one query
        raise UploadRejected(f"“{question.key}” is not asked on this page.")


def do_append_signed_answer_chunk(
    participant: Participant,
    trial: Trial,
    question: Question,
    take: str,
    offset: int,
    chunk: bytes,
    final: FinalChunk | None,
) -> tuple[int, Response | None]:
    """Append *chunk* of *take* at byte *offset*; with *final*, save the take as the answer.

    Return the stored length and, after the final chunk, the saved Response.
    """
    if participant.is_finished:
        raise UploadRejected(gettext("This study is finished; answers can no longer change."))
    _check_question(trial, question)
    take = take_id(take)
    with transaction.atomic(durable=True):
        # One writer per participant at a time: concurrent chunks cannot interleave.
        Participant.objects.select_for_update().get(pk=participant.pk)
        path = partial_path(participant, trial, question, take)
        if offset == 0:  # the take starts over, and every other take of the answer goes
            _discard_takes(participant, trial, question)
        stored = upload_offset(participant, trial, question, take)
        if offset != stored:
            raise UploadOffsetMismatch(stored)
        if stored + len(chunk) > MAX_SIGNED_ANSWER_BYTES:
            path.unlink(missing_ok=True)
            limit = MAX_SIGNED_ANSWER_BYTES // (1024 * 1024)
            raise UploadRejected(
                gettext("The recording is longer than %(limit)s MB allows.") % {"limit": limit}
            )
        path.parent.mkdir(parents=True, exist_ok=True)
        with open(path, "ab") as part:
            part.write(chunk)
            part.flush()
            os.fsync(part.fileno())
        stored += len(chunk)
    if final is None:
        return stored, None
    # Decoding takes a moment: outside the lock, so other participants' saves don't wait
    # on SQLite's single writer. A final chunk sent again after a failure here finds the
    # whole part stored (409 with its length) and sends an empty final chunk.
    suffix = _check_take(path, final)
    with tempfile.TemporaryDirectory() as folder:
        # A browser's WebM has no duration or seek index until it is remuxed.
        remuxed = Path(folder) / f"answer{suffix}"
        video = remuxed if suffix == ".webm" and remux_webm(path, remuxed) else path
        saved = _save_recording(participant, trial, question, take, video, stored, suffix)
    return stored, saved


def _check_take(path: Path, final: FinalChunk) -> str:
    """Return the video's extension if the stored take is what the browser sent, whole.

    Refused (and discarded): bytes whose SHA-256 is not the browser's, a file that is
    not WebM or MP4, one that does not decode to its end (cut short), and one whose
    decoded length is far from the length the browser measured.
    """
    digest = hashlib.sha256()
    with open(path, "rb") as part:
        head = part.read(64)
        part.seek(0)
        for block in iter(lambda: part.read(1 << 20), b""):
            digest.update(block)
    problem = ""
    kind = sniff(head)
    if digest.hexdigest() != final.sha256.lower():
        problem = "The recording arrived damaged (its checksum differs); please send it again."
    elif kind is None or kind.family != "video":
        problem = "The recording is not a WebM or MP4 video."
    else:
        duration_s = decoded_duration_s(path)
        if duration_s is None:
            problem = gettext(
                "The recording is incomplete or does not play; please record it again."
            )
        elif final.duration_ms is not None:
            claimed_s = final.duration_ms / 1000
            if abs(duration_s - claimed_s) > max(
                DURATION_TOLERANCE_S, DURATION_TOLERANCE_SHARE * claimed_s
            ):
                problem = gettext(
                    "The recording plays for %(played).1f s, not the %(recorded).1f s "
                    "recorded; please record it again."
                ) % {"played": duration_s, "recorded": claimed_s}
    if problem:
        path.unlink(missing_ok=True)
        raise UploadRejected(problem)
    return kind.suffix


def parse_final(sha256: object, duration_ms: object) -> FinalChunk:
    """Return the final chunk's claims from its headers; UploadRejected if malformed."""
    text = str(sha256 or "").strip().lower()
    if len(text) != 64 or any(c not in "0123456789abcdef" for c in text):
        raise UploadRejected("The last chunk does not give the recording's SHA-256.")
    duration = None
    if duration_ms not in (None, ""):
        try:
            duration = float(str(duration_ms))
        except ValueError:
            duration = math.nan
        if not (math.isfinite(duration) and 0 < duration <= 24 * 3600 * 1000):
            raise UploadRejected("The last chunk gives no valid length in milliseconds.")
    return FinalChunk(sha256=text, duration_ms=duration)


def _save_recording(
    participant: Participant,
    trial: Trial,
    question: Question,
    take: str,
    video: Path,
    length: int,
    suffix: str,
) -> Response:
    """Save *video*, the checked take as stored (remuxed), as the answer's video
    (replacing an older one); its SHA-256 is the stored file's."""
    with transaction.atomic():
        Participant.objects.select_for_update().get(pk=participant.pk)
        stored = upload_offset(participant, trial, question, take)
        if stored != length:  # the take started over meanwhile
            raise UploadOffsetMismatch(stored)
        response = Response.objects.select_for_update().filter(
            participant=participant, trial=trial, question=question
        ).first() or Response(participant=participant, trial=trial, question=question)
        old = response.video.name if response.video else ""
        # 128 random bits: the name alone never lets anyone guess another answer's file.
        name = f"{participant.pk}-{trial.key}-{question.key}-{secrets.token_hex(16)}{suffix}"
        with open(video, "rb") as part:
            response.video.save(name, File(part), save=False)
        response.video_sha256 = file_sha256(video)
        if response.pk:
            response.revision += 1
        response.save()
        _discard_takes(participant, trial, question)  # this take's part among them
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
