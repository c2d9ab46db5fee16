"""Save participants' answers idempotently: one response per participant, trial and question."""

from collections.abc import Mapping

from django.db import IntegrityError, transaction
from django.utils.translation import gettext

from studyplatform.lib.presentation import presented_conditions
from studyplatform.models import Participant, PersonalAnswer, Question, Response, Trial
from studyplatform.questions import Answer, AnswerRejected, Shown, question_type

ANSWER_FIELDS = ("chosen", "chosen_position", "rating", "number", "text", "score")


def do_save_response(
    participant: Participant, trial: Trial, question: Question, answer: Answer
) -> Response | PersonalAnswer:
    """Save *answer*, replacing the participant's earlier answer to the same question.

    Saving the same answer again changes nothing; a changed answer replaces the old one
    and counts a revision. Concurrent saves of one key leave exactly one row.
    """
    _check_page(participant, trial)
    values = _checked_values(participant, trial, question, answer)
    with transaction.atomic(durable=True):
        if question.is_personal:
            return _write_personal(participant, question, values["text"])
        key = {"participant": participant, "trial": trial, "question": question}
        existing = Response.objects.select_for_update().filter(**key).first()
        return _write_response(key, values, answer, existing)


def do_save_page_answers(
    participant: Participant, trial: Trial, answers: Mapping[Question, Answer]
) -> dict[str, str]:
    """Save the answers a page's form holds, in one transaction; return the messages of
    those rejected, by question key (the others are saved).

    Each answer is saved as :func:`do_save_response` saves it. The form repeats what
    the page saved as it was given, so the page's stored answers are read once, locked,
    and only the changed ones are written.
    """
    _check_page(participant, trial)
    errors, checked = {}, []
    for question, answer in answers.items():
        try:
            checked.append(
                (question, answer, _checked_values(participant, trial, question, answer))
            )
        except AnswerRejected as error:
            errors[question.key] = error.messages[0]
    if not checked:
        return errors
    with transaction.atomic(durable=True):
        shared = [question for question, _, _ in checked if not question.is_personal]
        stored = Response.objects.select_for_update().filter(
            participant=participant, trial=trial, question__in=shared
        )
        existing = {response.question_id: response for response in stored.order_by()}
        for question, answer, values in checked:
            if question.is_personal:
                _write_personal(participant, question, values["text"])
                continue
            key = {"participant": participant, "trial": trial, "question": question}
            _write_response(key, values, answer, existing.get(question.pk))
    return errors


def _check_page(participant: Participant, trial: Trial) -> None:
    """Raise AnswerRejected if *participant* may not answer on *trial* at all."""
    if trial.study_id != participant.study_id:
        raise AnswerRejected(gettext("This page is not part of your study."))
    if participant.is_finished:
        raise AnswerRejected(gettext("This study is finished; answers can no longer change."))


def _checked_values(
    participant: Participant, trial: Trial, question: Question, answer: Answer
) -> dict:
    """Return the Response fields *answer* sets, or raise AnswerRejected naming why not."""
    if question.pk not in {asked.pk for asked in trial.questions.all()}:  # prefetched or one query
        raise AnswerRejected(
            gettext("“%(question)s” is not asked on this page.") % {"question": question.key}
        )
    return question_type(question).response_values(
        question, answer, _shown(question, trial, participant)
    )


def _write_personal(participant: Participant, question: Question, value: str) -> PersonalAnswer:
    """Store a personal answer apart from the responses (changed only when it differs)."""
    personal, created = PersonalAnswer.objects.get_or_create(
        participant=participant, question=question, defaults={"value": value}
    )
    if not created and personal.value != value:
        personal.value = value
        personal.save(update_fields=["value"])
    return personal


def _write_response(key: dict, values: dict, answer: Answer, existing: Response | None) -> Response:
    """Insert the response of *key*, or revise *existing* if the answer changed."""
    if existing is None:
        try:
            # A savepoint, so that losing a race to a concurrent insert leaves the outer
            # transaction usable for the update below.
            with transaction.atomic():
                return Response.objects.create(
                    **key, **values, rt_ms=answer.rt_ms, answered_client_ms=answer.client_ms
                )
        except IntegrityError:
            existing = Response.objects.select_for_update().get(**key)
    if all(getattr(existing, name) == values[name] for name in ANSWER_FIELDS):
        return existing
    for name in ANSWER_FIELDS:
        setattr(existing, name, values[name])
    existing.rt_ms = answer.rt_ms
    existing.answered_client_ms = answer.client_ms
    existing.revision += 1
    existing.save(
        update_fields=[*ANSWER_FIELDS, "rt_ms", "answered_client_ms", "revision", "updated_at"]
    )
    return existing


def _shown(question: Question, trial: Trial, participant: Participant) -> Shown:
    """Return what *question*'s type needs of the page: the clips shown, the scored words."""
    kind = question_type(question)
    clips = presented_conditions(participant, trial) if kind.shows_clips else (None, None)
    target = trial.item.scoring_target if kind.is_scored and trial.item_id else ""
    return Shown(clips=clips, scoring_target=target)
