"""Delete participants' data: a withdrawal (everything) and retention (the personal part).

A participant may withdraw at any time: their responses, media events, personal answers
and signed-answer videos are deleted in one transaction, the videos once it commits, and
a Withdrawal row records what went (no personal data). A study's retention period
removes the personal part of finished participants' data when it expires.
"""

import logging
from dataclasses import dataclass
from datetime import datetime, timedelta

from django.db import transaction
from django.db.models import Q
from django.utils import timezone

from studyplatform.actions.media import delete_unused_files_on_commit
from studyplatform.models import (
    MediaEvent,
    Participant,
    PersonalAnswer,
    Response,
    Study,
    Withdrawal,
)

log = logging.getLogger(__name__)


def do_withdraw_participant(participant: Participant, *, by=None, reason: str = "") -> Withdrawal:
    """Delete everything *participant* gave and the participant; return the logged Withdrawal.

    *by* is the researcher who carries it out (None: the participant themself).
    """
    with transaction.atomic():
        locked = Participant.objects.select_for_update().get(pk=participant.pk)
        responses = Response.objects.filter(participant=locked)
        videos = [name for name in responses.values_list("video", flat=True) if name]
        withdrawal = Withdrawal.objects.create(
            study_id=locked.study_id,
            participant_number=locked.pk,
            withdrawn_by=by,
            reason=reason[:200],
            responses=responses.count(),
            events=MediaEvent.objects.filter(participant=locked).count(),
            personal_answers=PersonalAnswer.objects.filter(participant=locked).count(),
            files=len(videos),
        )
        locked.delete()  # responses, events and personal answers cascade
        delete_unused_files_on_commit(Response._meta.get_field("video").storage, videos)
    log.info("participant %s withdrew from study %s: %s responses, %s events, %s files deleted",
             withdrawal.participant_number, withdrawal.study_id, withdrawal.responses,
             withdrawal.events, withdrawal.files)  # fmt: skip
    return withdrawal


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
            Q(finished_at__lt=cutoff) | Q(finished_at__isnull=True, last_seen_at__lt=cutoff)
            | Q(finished_at__isnull=True, last_seen_at__isnull=True, started_at__lt=cutoff)
        )  # fmt: skip
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
        log.info("retention: recruitment ids of %s participants, %s personal answers and %s "
                 "videos deleted", cleared, personal, videos)  # fmt: skip
    return RetentionResult(cleared, personal, videos)
