"""Question types: one class per kind of question, found by the question's kind.

Add a question type: subclass :class:`QuestionType` (parse, check and show its answers,
name its widget template and its export kind), add the kind to ``Question.Kind`` with a
migration, and list the class in :data:`QUESTION_TYPES`.
"""

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

QUESTION_TYPES: dict[str, QuestionType] = {
    kind.kind: kind()
    for kind in (
        PairwiseQuestion,
        ComparativeQuestion,
        LikertQuestion,
        IntelligibilityQuestion,
        OpenQuestion,
        ChoiceQuestion,
        NumberQuestion,
        ShortTextQuestion,
        EmailQuestion,
    )
}


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
    "question_type",
]
