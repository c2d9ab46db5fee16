"""Question types: one class per kind of question, found by the question's kind.

Add a question type: subclass :class:`QuestionType` (parse, check and show its answers,
name its label, widget template, export kind and scale), list the class in
:data:`QUESTION_TYPES`, and write its template. ``Question.kind``'s choices, the design
builder's questions, the pages that may ask it and the docs' table are derived from
:data:`QUESTION_TYPES`; the system checks (``manage.py check``) refuse a type that does
not fit (:mod:`studyplatform.checks`).
"""

from contextlib import contextmanager

from studyplatform.questions.base import (
    MAX_TEXT_LENGTH,
    NO_DIFFERENCE,
    Answer,
    AnswerRejected,
    QuestionType,
    Shown,
)
from studyplatform.questions.clips import PairwiseQuestion
from studyplatform.questions.free import (
    EmailQuestion,
    IntelligibilityQuestion,
    NumberQuestion,
    OpenQuestion,
    ShortTextQuestion,
)
from studyplatform.questions.options import ChoiceQuestion, ComparativeQuestion, LikertQuestion
from studyplatform.questions.slider import SliderQuestion

QUESTION_TYPES: dict[str, QuestionType] = {
    kind.kind: kind()
    for kind in (
        PairwiseQuestion,
        ComparativeQuestion,
        LikertQuestion,
        SliderQuestion,
        IntelligibilityQuestion,
        OpenQuestion,
        ChoiceQuestion,
        NumberQuestion,
        ShortTextQuestion,
        EmailQuestion,
    )
}


def question_kind_choices() -> list[tuple[str, str]]:
    """Return ``Question.kind``'s choices: every registered kind with its label."""
    return [(kind, type_.label) for kind, type_ in QUESTION_TYPES.items()]


@contextmanager
def registered(type_: QuestionType):
    """Register *type_* for the duration of a ``with`` block (tests, a plug-in's trial)."""
    if type_.kind in QUESTION_TYPES:
        raise ValueError(f"Question kind {type_.kind!r} is registered already.")
    QUESTION_TYPES[type_.kind] = type_
    try:
        yield type_
    finally:
        del QUESTION_TYPES[type_.kind]


def question_type(question_or_kind) -> QuestionType:
    """Return the type of a question (or of a kind name)."""
    kind = getattr(question_or_kind, "kind", question_or_kind)
    try:
        return QUESTION_TYPES[kind]
    except KeyError:
        raise ValueError(f"Unknown question kind {kind!r}.") from None


__all__ = [
    "MAX_TEXT_LENGTH",
    "NO_DIFFERENCE",
    "QUESTION_TYPES",
    "Answer",
    "AnswerRejected",
    "QuestionType",
    "Shown",
    "question_kind_choices",
    "question_type",
    "registered",
]
