"""Save participants' answers idempotently: one response per participant, trial and question."""

from collections.abc import Mapping
from dataclasses import dataclass

from django.core.exceptions import ValidationError
from django.db import IntegrityError, transaction

from analysis.intelligibility import word_accuracy
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
ANSWER_FIELDS = ("chosen", "chosen_position", "rating", "number", "text", "score")


def schedule_entry(participant: Participant, trial: Trial) -> dict | None:
    """Return the participant's schedule entry of *trial*, or None if they are not shown it."""
    for entry in participant.schedule:
        if isinstance(entry, dict) and entry.get("trial") == trial.key:
            return entry
    return None


def presented_conditions(
    participant: Participant, trial: Trial, conditions: Mapping[str, Condition] | None = None
) -> tuple[Condition | None, Condition | None]:
    """Return the conditions shown as Clip 1 and Clip 2 to *participant* on *trial*.

    The participant's stored schedule says whether the trial's clips were swapped
    (``"swap": true``) and, under Latin-square rotation, which conditions were shown
    (``"a"``, ``"b"``); without an entry the trial's own clips show in order.
    *conditions* (the study's, by key) saves a query per call.
    """
    entry = schedule_entry(participant, trial) or {}
    first, second = trial.condition_a, trial.condition_b
    if "a" in entry:
        if conditions is None:
            keys = [entry["a"], entry.get("b")]
            found = Condition.objects.filter(study_id=trial.study_id, key__in=keys)
            conditions = {condition.key: condition for condition in found}
        first, second = conditions.get(entry["a"]), conditions.get(entry.get("b"))
    if entry.get("swap"):
        return second, first
    return first, second


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
        "score": None,
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
        allowed = {option.value for option in question.options.all()}
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
        if kind == Question.Kind.INTELLIGIBILITY and trial.item is not None and text:
            score = word_accuracy(text, trial.item.scoring_target)
            values["score"] = None if score != score else score
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
    if question.pk not in {asked.pk for asked in trial.questions.all()}:  # prefetched or one query
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
