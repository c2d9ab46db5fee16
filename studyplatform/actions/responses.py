"""Save participants' answers idempotently: one response per participant, trial and question."""

from dataclasses import dataclass

from django.core.exceptions import ValidationError
from django.db import IntegrityError, transaction

from studyplatform.models import Condition, Participant, PersonalAnswer, Question, Response, Trial


class AnswerRejected(ValidationError):
    """An answer that does not fit its question or trial; nothing was saved."""


@dataclass(frozen=True)
class Answer:
    """What a participant gave for one question; unused fields stay empty."""

    choice_position: int | None = None  # pairwise: 1, 2, or 0 for "cannot see a difference"
    rating: int | None = None  # the value of a scale point or choice option
    number: float | None = None
    text: str = ""
    rt_ms: int | None = None


MAX_TEXT_LENGTH = 10_000
ANSWER_FIELDS = ("chosen", "chosen_position", "rating", "number", "text")


def presented_conditions(participant: Participant, trial: Trial) -> tuple[Condition, Condition]:
    """Return the conditions shown as Clip 1 and Clip 2 to *participant* on *trial*.

    The participant's stored schedule says whether the trial's clips were swapped
    (entries ``{"trial": key, "swap": true}``); without an entry they are not.
    """
    swapped = any(
        entry.get("trial") == trial.key and entry.get("swap")
        for entry in participant.schedule
        if isinstance(entry, dict)
    )
    if swapped:
        return trial.condition_b, trial.condition_a
    return trial.condition_a, trial.condition_b


def _response_values(
    participant: Participant, trial: Trial, question: Question, answer: Answer
) -> dict:
    """Check *answer* against *question* and return the Response fields it sets."""
    kind = question.kind
    values: dict = {
        "chosen": "",
        "chosen_position": None,
        "rating": None,
        "number": None,
        "text": "",
    }
    if kind == Question.Kind.PAIRWISE:
        position = answer.choice_position
        if position == 0 and question.allow_no_difference:
            values["chosen"] = Response.NO_DIFFERENCE
        elif position in (1, 2):
            clips = presented_conditions(participant, trial)
            values["chosen"] = clips[position - 1].key
            values["chosen_position"] = position
        else:
            raise AnswerRejected(f"“{position}” is not one of the clips on this page.")
    elif question.uses_options:
        allowed = set(question.options.values_list("value", flat=True))
        if answer.rating not in allowed:
            raise AnswerRejected(
                f"“{answer.rating}” is not a point of the scale of “{question.key}”."
            )
        values["rating"] = answer.rating
    elif kind == Question.Kind.NUMBER:
        number = answer.number
        if number is None or number != number:
            raise AnswerRejected(f"“{question.key}” needs a number.")
        if (question.min_value is not None and number < question.min_value) or (
            question.max_value is not None and number > question.max_value
        ):
            low = "−∞" if question.min_value is None else f"{question.min_value:g}"
            high = "∞" if question.max_value is None else f"{question.max_value:g}"
            raise AnswerRejected(f"{number:g} is outside the allowed range {low} to {high}.")
        values["number"] = number
    else:
        text = answer.text.strip()
        if len(text) > MAX_TEXT_LENGTH:
            raise AnswerRejected(f"The answer is longer than {MAX_TEXT_LENGTH} characters.")
        if not text and question.required:
            raise AnswerRejected(f"“{question.key}” needs an answer.")
        values["text"] = text
    return values


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
    if not trial.questions.filter(pk=question.pk).exists():
        raise AnswerRejected(f"“{question.key}” is not asked on this page.")
    values = _response_values(participant, trial, question, answer)

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
                    return Response.objects.create(**key, **values, rt_ms=answer.rt_ms)
            except IntegrityError:
                existing = Response.objects.select_for_update().get(**key)
        if all(getattr(existing, name) == values[name] for name in ANSWER_FIELDS):
            return existing
        for name in ANSWER_FIELDS:
            setattr(existing, name, values[name])
        existing.rt_ms = answer.rt_ms
        existing.revision += 1
        existing.save(update_fields=[*ANSWER_FIELDS, "rt_ms", "revision", "updated_at"])
        return existing
