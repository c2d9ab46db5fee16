"""Enroll participants in a study and move them through its pages."""

import secrets
from collections.abc import Mapping

from django.core.exceptions import ValidationError
from django.db import transaction
from django.utils import timezone
from django.utils.translation import gettext

from studyplatform.lib.participants import (
    PageRejected,
    clean_recruitment_params,
    closed_reason,
    missing_answers,
    page_count,
    unwatched_clips,
)
from studyplatform.lib.schedule import build_schedule
from studyplatform.models import (
    Participant,
    Study,
    Trial,
)


def do_enroll_participant(
    study: Study,
    *,
    recruitment_params: Mapping[str, str] | None = None,
    user_agent: str = "",
    consented: bool = False,
) -> Participant:
    """Create a participant with a fresh token, seed and schedule in a pilot or open study.

    The schedule is drawn from the seed and the enrollment number (the Latin-square row)
    and stored; *consented* records consent now (the welcome page's button).
    """
    if not study.is_accepting_participants:
        raise ValidationError(
            gettext("The study “%(title)s” is not taking participants now.")
            % {"title": study.title}
        )
    with transaction.atomic(durable=True):
        participant = Participant(
            study=study,
            recruitment_params=clean_recruitment_params(recruitment_params or {}),
            is_pilot=study.status == Study.Status.PILOT,
            language=(
                Participant.Language.ASL_ENGLISH
                if study.asl_first
                else Participant.Language.ENGLISH
            ),
            user_agent=user_agent[:400],
        )
        # The enrollment number is the Latin-square row: lock the study so that two
        # participants enrolling at once count one after the other (PostgreSQL; SQLite
        # takes its write lock when the transaction begins).
        Study.objects.select_for_update().filter(pk=study.pk).values_list("pk").first()
        enrollment = Participant.objects.filter(study=study).count()
        participant.schedule = build_schedule(study, participant.seed, enrollment)
        if consented:
            now = timezone.now()
            participant.consented_at = participant.last_seen_at = now
            participant.position = participant.reached = 1
        participant.save()
        return participant


def do_advance_participant(participant: Participant, page: int, trial: Trial | None) -> int:
    """Move the participant on from *page* (whose trial is *trial*); return the next page.

    Repeating the move (a double click, a re-posted form) changes nothing and returns
    the same page. Leaving the last page finishes the session. *participant* is brought
    up to date with the stored row.
    """
    with transaction.atomic(durable=True):
        locked = _locked(participant)
        if locked.is_finished or page < locked.position:
            _follow(participant, locked)
            return locked.position  # moved on already: a repeated Next
        if page > locked.position:
            raise PageRejected(gettext("You have not reached this page yet."))
        reason = closed_reason(locked)
        if reason:
            raise PageRejected(reason)
        if trial is not None:
            # Watching comes first: until the clips have ended, the questions are disabled,
            # so "answer every question" would name the wrong reason.
            watch = locked.study.require_full_view and trial.condition_a_id and trial.item_id
            if watch and unwatched_clips(locked, trial):
                raise PageRejected(gettext("Please watch each clip to its end before going on."))
            missing = missing_answers(locked, trial)
            if missing:
                raise PageRejected(
                    gettext("Please answer every question on this page first."),
                    params={"questions": [q.key for q in missing]},
                )
        now = timezone.now()
        locked.position = page + 1
        locked.reached = max(locked.reached, locked.position)
        locked.last_seen_at = now
        if locked.position > page_count(locked):
            locked.finished_at = now
            locked.completion_code = _completion_code(locked.study)
        locked.save(update_fields=list(MOVE_FIELDS))
        if locked.finished_at == now and not locked.is_pilot:
            _close_at_target(locked.study)
    _follow(participant, locked)
    return locked.position


def do_go_back_participant(participant: Participant, page: int) -> int:
    """Move the participant back to *page*, if the study lets them; return it."""
    with transaction.atomic(durable=True):
        locked = _locked(participant)
        if not locked.study.allow_back:
            raise PageRejected(gettext("This study does not let you go back to earlier pages."))
        if locked.is_finished:
            raise PageRejected(gettext("This study is finished; answers can no longer change."))
        if not 1 <= page <= locked.reached:
            raise PageRejected(gettext("You have not reached this page yet."))
        locked.position = page
        locked.last_seen_at = timezone.now()
        locked.save(update_fields=["position", "last_seen_at"])
    _follow(participant, locked)
    return page


# The fields a move may change.
MOVE_FIELDS = ("position", "reached", "last_seen_at", "finished_at", "completion_code")

# Unambiguous characters for participant codes (no 0/O, 1/I/L): read off a screen, typed.
CODE_ALPHABET = "23456789ABCDEFGHJKMNPQRSTUVWXYZ"


def _completion_code(study: Study) -> str:
    """Return the code a finishing participant is shown: the study's, or their own."""
    if not study.unique_completion_codes:
        return study.completion_code
    own = "".join(secrets.choice(CODE_ALPHABET) for _ in range(8))
    return f"{study.completion_code}-{own}" if study.completion_code else own


def _close_at_target(study: Study) -> None:
    """Close an open study once its target number of participants have finished.

    Pilot and rejected participants do not count. Participants already taking part may
    finish: a closed study refuses only new ones.
    """
    if study.target_n is None or study.status != Study.Status.OPEN:
        return
    finished = Participant.objects.filter(
        study=study, is_pilot=False, finished_at__isnull=False
    ).exclude(review=Participant.Review.REJECTED)
    if finished.count() >= study.target_n:
        Study.objects.filter(pk=study.pk, status=Study.Status.OPEN).update(
            status=Study.Status.CLOSED
        )


def _locked(participant: Participant) -> Participant:
    """Read and lock the participant's row (only it), with the study, for a move."""
    return (
        Participant.objects.select_related("study")
        .select_for_update(of=("self",))
        .get(pk=participant.pk)
    )


def _follow(participant: Participant, stored: Participant) -> None:
    """Bring the caller's *participant* up to the row a move read or wrote."""
    for name in MOVE_FIELDS:
        setattr(participant, name, getattr(stored, name))


def do_set_participant_language(participant: Participant, language: str) -> None:
    """Switch the participant between ASL + English and English only."""
    if participant.is_finished:
        raise ValidationError(gettext("This study is finished; nothing about it can change now."))
    if language not in Participant.Language.values:
        raise ValidationError(f"Unknown language “{language}”.")
    if language == Participant.Language.ENGLISH and not participant.study.allow_english_only:
        raise ValidationError(gettext("This study does not offer its written text alone."))
    Participant.objects.filter(pk=participant.pk).update(language=language)
    participant.language = language
