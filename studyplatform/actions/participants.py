"""Enroll participants in a study and move them through its pages."""

import re
from collections.abc import Mapping
from datetime import timedelta
from urllib.parse import quote

from django.core.exceptions import ValidationError
from django.db import transaction
from django.utils import timezone

from studyplatform.models import (
    MediaEvent,
    Participant,
    PersonalAnswer,
    Question,
    Response,
    Study,
    Trial,
)
from studyplatform.schedule import build_schedule

# Longest recruitment parameter kept, in characters: ids from recruitment services are
# short; anything longer is not an id and is not stored.
MAX_PARAM_LENGTH = 200
MAX_PARAMS = 20
# A one-sitting study closes for a participant who leaves it this long between pages.
ONE_SITTING_BREAK = timedelta(minutes=30)
# Under a time limit, the page warns the participant when this much time is left.
TIME_LOW = timedelta(minutes=5)


def clean_recruitment_params(params: Mapping[str, str]) -> dict[str, str]:
    """Return the URL parameters worth keeping (e.g. PROLIFIC_PID), bounded in size."""
    kept: dict[str, str] = {}
    for name, value in params.items():
        if len(kept) >= MAX_PARAMS:
            break
        if not name or len(name) > 64 or len(value) > MAX_PARAM_LENGTH:
            continue
        kept[name] = value
    return kept


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
        raise ValidationError(f"The study “{study.title}” is not taking participants now.")
    with transaction.atomic():
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


class PageRejected(ValidationError):
    """A move to a page the participant may not go to; nothing changed."""


def page_count(participant: Participant) -> int:
    """Return the number of scheduled pages (the thank-you page is number count + 1)."""
    return len(participant.schedule)


def time_left(participant: Participant, now=None) -> timedelta | None:
    """Return how long the participant has left under the study's time limit, or None.

    The limit runs from consent; None when the study has no limit (or before consent).
    """
    limit = participant.study.time_limit_minutes
    if not limit or participant.consented_at is None:
        return None
    deadline = participant.consented_at + timedelta(minutes=limit)
    return max(deadline - (now or timezone.now()), timedelta(0))


def closed_reason(participant: Participant, now=None) -> str:
    """Return why the participant can no longer answer (time limit, sitting), or ""."""
    study = participant.study
    now = now or timezone.now()
    if participant.is_finished:
        return ""
    if time_left(participant, now) == timedelta(0):
        return f"The time limit of {study.time_limit_minutes} minutes has passed."
    if (
        study.one_sitting
        and participant.last_seen_at is not None
        and now > participant.last_seen_at + ONE_SITTING_BREAK
    ):
        minutes = int(ONE_SITTING_BREAK.total_seconds() // 60)
        return (
            f"This study must be completed in one sitting, and more than {minutes} "
            "minutes passed since your last page."
        )
    return ""


def page_trial(participant: Participant, page: int, for_answer: bool = False) -> Trial:
    """Return the trial on the participant's *page*, if they may see (or answer) it.

    Raise PageRejected for a page they have not reached, and, when answering, for an
    earlier page of a study that does not let participants go back, or a finished one.
    The page's questions come along, and their options too unless *for_answer* (one
    answer needs at most one question's options).
    """
    if not 1 <= page <= page_count(participant):
        raise PageRejected(f"There is no page {page} in this study.")
    if page > participant.reached:
        raise PageRejected("You have not reached this page yet.")
    if for_answer:
        if participant.is_finished:
            raise PageRejected("This study is finished; answers can no longer change.")
        if page != participant.position and not participant.study.allow_back:
            raise PageRejected("This study does not let you change answers on earlier pages.")
        reason = closed_reason(participant)
        if reason:
            raise PageRejected(reason)
    key = participant.schedule[page - 1].get("trial")
    # One query for the page, with the clips and questions it shows; unordered (the
    # key is unique in the study), as ordering would join the block or sort by pk.
    found = (
        Trial.objects.filter(study_id=participant.study_id, key=key)
        .select_related("block", "item", "condition_a", "condition_b")
        .prefetch_related("questions" if for_answer else "questions__options")
        .order_by()[:1]
    )
    trial = next(iter(found), None)
    if trial is None:
        raise PageRejected(f"Page {page} was removed from the study.")
    return trial


def missing_answers(participant: Participant, trial: Trial) -> list[Question]:
    """Return the required questions of *trial* the participant has not answered."""
    required = [q for q in trial.questions.all() if q.required]
    if not required:
        return []
    answered = set(
        Response.objects.filter(participant=participant, trial=trial).values_list(
            "question_id", flat=True
        )
    )
    personal = [q.pk for q in required if q.is_personal]
    if personal:
        answered |= set(
            PersonalAnswer.objects.filter(
                participant=participant, question_id__in=personal
            ).values_list("question_id", flat=True)
        )
    return [q for q in required if q.pk not in answered]


def unwatched_clips(participant: Participant, trial: Trial) -> list[int]:
    """Return the clip positions of *trial* the participant has not watched to the end."""
    positions = [1, 2] if trial.condition_b_id else [1]
    ended = set(
        MediaEvent.objects.filter(
            participant=participant, trial=trial, kind=MediaEvent.Kind.ENDED
        ).values_list("clip_position", flat=True)
    )
    return [position for position in positions if position not in ended]


def do_advance_participant(participant: Participant, page: int, trial: Trial | None) -> int:
    """Move the participant on from *page* (whose trial is *trial*); return the next page.

    Repeating the move (a double click, a re-posted form) changes nothing and returns
    the same page. Leaving the last page finishes the session. *participant* is brought
    up to date with the stored row.
    """
    with transaction.atomic():
        locked = _locked(participant)
        if locked.is_finished or page < locked.position:
            _follow(participant, locked)
            return locked.position  # moved on already: a repeated Next
        if page > locked.position:
            raise PageRejected("You have not reached this page yet.")
        reason = closed_reason(locked)
        if reason:
            raise PageRejected(reason)
        if trial is not None:
            missing = missing_answers(locked, trial)
            if missing:
                raise PageRejected(
                    "Please answer every question on this page first.",
                    params={"questions": [q.key for q in missing]},
                )
            watch = locked.study.require_full_view and trial.condition_a_id and trial.item_id
            if watch and unwatched_clips(locked, trial):
                raise PageRejected("Please watch each clip to its end before going on.")
        now = timezone.now()
        locked.position = page + 1
        locked.reached = max(locked.reached, locked.position)
        locked.last_seen_at = now
        if locked.position > page_count(locked):
            locked.finished_at = now
        locked.save(update_fields=list(MOVE_FIELDS))
    _follow(participant, locked)
    return locked.position


def do_go_back_participant(participant: Participant, page: int) -> int:
    """Move the participant back to *page*, if the study lets them; return it."""
    with transaction.atomic():
        locked = _locked(participant)
        if not locked.study.allow_back:
            raise PageRejected("This study does not let you go back to earlier pages.")
        if locked.is_finished:
            raise PageRejected("This study is finished; answers can no longer change.")
        if not 1 <= page <= locked.reached:
            raise PageRejected("You have not reached this page yet.")
        locked.position = page
        locked.last_seen_at = timezone.now()
        locked.save(update_fields=["position", "last_seen_at"])
    _follow(participant, locked)
    return page


# The fields a move may change.
MOVE_FIELDS = ("position", "reached", "last_seen_at", "finished_at")


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
    if language not in Participant.Language.values:
        raise ValidationError(f"Unknown language “{language}”.")
    if language == Participant.Language.ENGLISH and not participant.study.allow_english_only:
        raise ValidationError("This study is presented in ASL and English only.")
    Participant.objects.filter(pk=participant.pk).update(language=language)
    participant.language = language


def completion_url(participant: Participant) -> str:
    """Return the study's redirect URL with the participant's recruitment parameters in it.

    ``{PROLIFIC_PID}`` becomes the URL-quoted value the participant arrived with; names
    the participant did not bring become empty.
    """
    template = participant.study.redirect_url
    params = participant.recruitment_params or {}
    return re.sub(
        r"\{([A-Za-z0-9_]+)\}", lambda m: quote(str(params.get(m.group(1), "")), safe=""), template
    )
