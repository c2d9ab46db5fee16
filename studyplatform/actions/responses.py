"""Save participants' answers idempotently: one response per participant, trial and question."""

from django.db import IntegrityError, transaction

from studyplatform.models import Participant, PersonalAnswer, Question, Response, Trial
from studyplatform.questions import Answer, AnswerRejected, question_type

ANSWER_FIELDS = ("chosen", "chosen_position", "rating", "number", "text", "score")


def do_save_response(
    participant: Participant, trial: Trial, question: Question, answer: Answer
) -> Response | PersonalAnswer:
    """Save *answer*, replacing the participant's earlier answer to the same question.

    Saving the same answer again changes nothing; a changed answer replaces the old one
    and counts a revision. Concurrent saves of one key leave exactly one row.
    """
    if trial.study_id != participant.study_id:
        raise AnswerRejected("This page is not part of your study.")
    if participant.is_finished:
        raise AnswerRejected("This study is finished; answers can no longer change.")
    if question.pk not in {asked.pk for asked in trial.questions.all()}:  # prefetched or one query
        raise AnswerRejected(f"“{question.key}” is not asked on this page.")
    values = question_type(question).response_values(question, answer, participant, trial)

    if question.is_personal:
        with transaction.atomic():
            personal, _ = PersonalAnswer.objects.update_or_create(
                participant=participant, question=question, defaults={"value": values["text"]}
            )
        return personal

    key = {"participant": participant, "trial": trial, "question": question}
    with transaction.atomic():
        existing = Response.objects.select_for_update().filter(**key).first()
        if existing is None:
            try:
                # A savepoint, so that losing a race to a concurrent insert leaves the
                # outer transaction usable for the update below.
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
