"""Read where a participant stands: pages, time left, what they may still answer."""

import re
from collections.abc import Mapping
from datetime import timedelta
from urllib.parse import quote

from django.core.exceptions import ValidationError
from django.utils import timezone
from django.utils.translation import gettext

from studyplatform.models import (
    MediaEvent,
    Participant,
    PersonalAnswer,
    Question,
    Response,
    Study,
    Trial,
)

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


MOBILE_MARKERS = ("Mobi", "Android", "iPhone", "iPad")


def device_problem(study: Study, user_agent: str) -> str:
    """Return why *study* cannot be taken on the device *user_agent* names, or ""."""
    mobile = any(marker in user_agent for marker in MOBILE_MARKERS)
    if study.allowed_devices == Study.Devices.DESKTOP and mobile:
        return gettext("Please take this study on a desktop or laptop computer.")
    if study.allowed_devices == Study.Devices.MOBILE and not mobile:
        return gettext("Please take this study on a phone or tablet.")
    return ""


def closed_reason(participant: Participant, now=None) -> str:
    """Return why the participant can no longer answer (time limit, sitting), or ""."""
    study = participant.study
    now = now or timezone.now()
    if participant.is_finished:
        return ""
    if time_left(participant, now) == timedelta(0):
        return gettext("The time limit of %(minutes)s minutes has passed.") % {
            "minutes": study.time_limit_minutes
        }
    if (
        study.one_sitting
        and participant.last_seen_at is not None
        and now > participant.last_seen_at + ONE_SITTING_BREAK
    ):
        minutes = int(ONE_SITTING_BREAK.total_seconds() // 60)
        return gettext(
            "This study must be completed in one sitting, and more than %(minutes)s "
            "minutes passed since your last page."
        ) % {"minutes": minutes}
    return ""


def page_trial(participant: Participant, page: int, for_answer: bool = False) -> Trial:
    """Return the trial on the participant's *page*, if they may see (or answer) it.

    Raise PageRejected for a page they have not reached, and, when answering, for an
    earlier page of a study that does not let participants go back, or a finished one.
    The page's questions come along, and their options too unless *for_answer* (one
    answer needs at most one question's options).
    """
    if not 1 <= page <= page_count(participant):
        raise PageRejected(gettext("There is no page %(page)s in this study.") % {"page": page})
    if page > participant.reached:
        raise PageRejected(gettext("You have not reached this page yet."))
    if for_answer:
        if participant.is_finished:
            raise PageRejected(gettext("This study is finished; answers can no longer change."))
        if page != participant.position and not participant.study.allow_back:
            raise PageRejected(
                gettext("This study does not let you change answers on earlier pages.")
            )
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
        raise PageRejected(gettext("Page %(page)s was removed from the study.") % {"page": page})
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


def completion_url(participant: Participant) -> str:
    """Return the study's redirect URL with the participant's recruitment parameters in it.

    ``{PROLIFIC_PID}`` becomes the URL-quoted value the participant arrived with, and
    ``{CODE}`` their completion code; names the participant did not bring become empty.
    """
    template = participant.study.redirect_url
    code = participant.completion_code or participant.study.completion_code
    params = {**(participant.recruitment_params or {}), "CODE": code}
    return re.sub(
        r"\{([A-Za-z0-9_]+)\}", lambda m: quote(str(params.get(m.group(1), "")), safe=""), template
    )


def participant_by_token(token: str) -> Participant | None:
    """Return the participant whose link holds *token* (with their study), or None."""
    # Sliced, not .first(): the token is unique, and first()'s ORDER BY pk costs a
    # noticeable share of compiling this query on every request.
    found = Participant.objects.select_related("study").filter(token=token).order_by()[:1]
    return next(iter(found), None)
