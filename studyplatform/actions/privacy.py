"""Delete participants' data: a withdrawal (everything) and retention (the personal part).

A participant may withdraw at any time: their responses, media events, personal answers,
signed-answer videos, unfinished uploads and the browser sessions that remember them are
deleted in one transaction, the files once it commits, and a Withdrawal row and a line
of the withdrawal ledger (:mod:`studyplatform.files.ledger`) record what went (no personal
data). A restore re-applies the ledger (:func:`do_reapply_withdrawals`), so restoring an
older backup brings nobody back. A study's retention period removes the personal part of
finished participants' data when it expires.
"""

import logging
from dataclasses import dataclass
from datetime import datetime, timedelta

from django.conf import settings
from django.db import transaction
from django.db.models import Q
from django.utils import timezone

from studyplatform.actions.media import delete_unused_files_on_commit
from studyplatform.actions.uploads import discard_partial_uploads, partial_uploads
from studyplatform.files import ledger
from studyplatform.models import (
    MediaEvent,
    Participant,
    PersonalAnswer,
    Response,
    Study,
    Withdrawal,
)
from studyplatform.models.participants import PARTICIPANT_SESSION_KEY

log = logging.getLogger(__name__)


def do_withdraw_participant(participant: Participant, *, by=None, reason: str = "") -> Withdrawal:
    """Delete everything *participant* gave and the participant; return the logged Withdrawal.

    *by* is the researcher who carries it out (None: the participant themself).
    """
    with transaction.atomic(durable=True):
        locked = Participant.objects.select_for_update().get(pk=participant.pk)
        responses = Response.objects.filter(participant=locked)
        videos = _answer_videos(locked)
        partials = len(partial_uploads(locked.pk))
        withdrawal = Withdrawal.objects.create(
            study_id=locked.study_id,
            participant_number=locked.pk,
            withdrawn_by=by,
            reason=reason[:200],
            responses=responses.count(),
            events=MediaEvent.objects.filter(participant=locked).count(),
            personal_answers=PersonalAnswer.objects.filter(participant=locked).count(),
            files=len(videos) + partials,
        )
        entry = ledger.LedgerEntry(
            study_id=locked.study_id,
            participant_number=locked.pk,
            token_sha256=ledger.token_sha256(locked.token),
            withdrawn_at=withdrawal.withdrawn_at.isoformat(),
            withdrawn_by=getattr(by, "username", None),
            reason=withdrawal.reason,
            responses=withdrawal.responses,
            events=withdrawal.events,
            personal_answers=withdrawal.personal_answers,
            files=withdrawal.files,
        )
        forget_in_sessions({locked.token})
        _erase(locked, videos)
        transaction.on_commit(lambda: ledger.append(entry))
    log.info(
        "participant %s withdrew from study %s: %s responses, %s events, %s files deleted",
        withdrawal.participant_number,
        withdrawal.study_id,
        withdrawal.responses,
        withdrawal.events,
        withdrawal.files,
    )
    return withdrawal


def _answer_videos(participant: Participant) -> list[str]:
    """Return the names of *participant*'s signed-answer videos."""
    names = Response.objects.filter(participant=participant).values_list("video", flat=True)
    return [name for name in names if name]


def _erase(participant: Participant, videos: list[str]) -> None:
    """Delete *participant* (rows cascade), and once committed their files."""
    number = participant.pk
    participant.delete()  # responses, events and personal answers cascade
    delete_unused_files_on_commit(Response._meta.get_field("video").storage, videos)
    transaction.on_commit(lambda: discard_partial_uploads(number))


def forget_in_sessions(tokens: set[str]) -> int:
    """Remove *tokens* from every stored browser session; return how many sessions changed.

    A session remembers the participant it took part as (to lead the study's link back
    to them); after a withdrawal nothing may lead anywhere. Sessions kept in cookies or a
    cache are out of the server's reach; the database's are searched.
    """
    if settings.SESSION_ENGINE != "django.contrib.sessions.backends.db":
        return 0
    from django.contrib.sessions.backends.db import SessionStore
    from django.contrib.sessions.models import Session

    changed = 0
    store = SessionStore()
    for session in Session.objects.iterator():
        data = session.get_decoded()
        remembered = data.get(PARTICIPANT_SESSION_KEY)
        if not isinstance(remembered, dict) or not tokens & set(remembered.values()):
            continue
        data[PARTICIPANT_SESSION_KEY] = {
            slug: token for slug, token in remembered.items() if token not in tokens
        }
        Session.objects.filter(pk=session.pk).update(session_data=store.encode(data))
        changed += 1
    return changed


@dataclass(frozen=True)
class Reapplied:
    """What re-applying the withdrawal ledger did after a restore."""

    participants: tuple[int, ...]  # the numbers of those withdrawn again
    logged: int  # withdrawals missing from the restored log and written back into it


def do_reapply_withdrawals(entries: list[ledger.LedgerEntry]) -> Reapplied:
    """Withdraw again every participant of *entries* that the database holds; log each.

    Run after a restore: a backup made before a withdrawal holds the participant and not
    the Withdrawal row. Both are put right; the files go once the transaction commits.
    """
    by_hash = {entry.token_sha256: entry for entry in entries}
    withdrawn = []
    logged = 0
    with transaction.atomic():
        present = {
            (w.study_id, w.participant_number)
            for w in Withdrawal.objects.only("study_id", "participant_number")
        }
        studies = set(Study.objects.values_list("pk", flat=True))
        tokens = set()
        for participant in Participant.objects.select_for_update().order_by("pk"):
            if ledger.token_sha256(participant.token) not in by_hash:
                continue
            withdrawn.append(participant.pk)
            tokens.add(participant.token)
            _erase(participant, _answer_videos(participant))
        forget_in_sessions(tokens)
        for entry in entries:
            key = (entry.study_id, entry.participant_number)
            if key in present or entry.study_id not in studies:
                continue
            row = Withdrawal.objects.create(
                study_id=entry.study_id,
                participant_number=entry.participant_number,
                reason=entry.reason,
                responses=entry.responses,
                events=entry.events,
                personal_answers=entry.personal_answers,
                files=entry.files,
            )
            # auto_now_add stamps the restore's time; the log keeps the withdrawal's.
            Withdrawal.objects.filter(pk=row.pk).update(withdrawn_at=entry.withdrawn_at)
            present.add(key)
            logged += 1
    if withdrawn:
        log.warning(
            "restore: %s withdrawn participants were in the backup and were withdrawn again: %s",
            len(withdrawn),
            withdrawn,
        )
    return Reapplied(participants=tuple(withdrawn), logged=logged)


@dataclass(frozen=True)
class RetentionResult:
    """What one retention run deleted, over all studies."""

    recruitment_ids: int  # participants whose recruitment parameters were cleared
    personal_answers: int
    videos: int


def do_apply_retention(now: datetime | None = None) -> RetentionResult:
    """Delete personal data whose study's retention period has passed."""
    now = now or timezone.now()
    cleared = personal = videos = 0
    studies = Study.objects.filter(personal_data_retention_days__isnull=False)
    for study in studies:
        cutoff = now - timedelta(days=study.personal_data_retention_days)
        # Finished before the cutoff, or left unfinished with no visit since.
        expired = Participant.objects.filter(study=study).filter(
            Q(finished_at__lt=cutoff)
            | Q(finished_at__isnull=True, last_seen_at__lt=cutoff)
            | Q(finished_at__isnull=True, last_seen_at__isnull=True, started_at__lt=cutoff)
        )
        with transaction.atomic():
            answers = PersonalAnswer.objects.filter(participant__in=expired)
            signed = Response.objects.filter(participant__in=expired).exclude(video="")
            names = list(signed.values_list("video", flat=True))
            personal += answers.count()
            videos += len(names)
            answers.delete()
            signed.update(video="")
            cleared += expired.exclude(recruitment_params={}).update(recruitment_params={})
            delete_unused_files_on_commit(Response._meta.get_field("video").storage, names)
    if cleared or personal or videos:
        log.info(
            "retention: recruitment ids of %s participants, %s personal answers and %s "
            "videos deleted",
            cleared,
            personal,
            videos,
        )
    return RetentionResult(cleared, personal, videos)
