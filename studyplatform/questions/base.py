"""What every question type does: parse a posted answer, check it, show it, export it.

A question type is one class per :class:`~studyplatform.models.Question` kind; the
participant view, the save action, the page layout, the export and the templates ask
the type instead of branching on the kind. A question type reads nothing from the
database: what it needs of the page (the clips shown) is handed to it as :class:`Shown`.
"""

import math
import re
from dataclasses import dataclass

from django.core.exceptions import ValidationError


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
    client_ms: int | None = None  # when it was given, on the browser's clock


@dataclass(frozen=True)
class Shown:
    """What the page an answer comes from showed: the conditions as Clip 1 and Clip 2
    (for question types with *shows_clips*) and the words a scored answer is scored
    against (for those with *is_scored*)."""

    clips: tuple = (None, None)
    scoring_target: str = ""


# A pairwise answer of "Cannot see a difference", stored in place of a condition's key.
NO_DIFFERENCE = "none"
MAX_TEXT_LENGTH = 10_000
# A personal answer (name, e-mail) is stored in PersonalAnswer.value, a 300-character
# column that SQLite would not enforce.
MAX_PERSONAL_LENGTH = 300
MAX_KIND_LENGTH = 20  # Question.kind's column

_ASCII_INTEGER = re.compile(r"[+-]?[0-9]{1,12}")
_ASCII_NUMBER = re.compile(r"[+-]?([0-9]+\.?[0-9]*|\.[0-9]+)([eE][+-]?[0-9]{1,3})?")


def parse_integer(value: str) -> int:
    """Return *value* as an integer written in ASCII digits; ValueError otherwise.

    Python's ``int`` also reads other scripts' digits ("٣" is 3), underscores and
    padding, none of which a page's control sends.
    """
    if not _ASCII_INTEGER.fullmatch(value):
        raise ValueError(value)
    return int(value)


def parse_number(value: str) -> float:
    """Return *value* as a finite decimal number written in ASCII; ValueError otherwise."""
    if not _ASCII_NUMBER.fullmatch(value):
        raise ValueError(value)
    number = float(value)
    if not math.isfinite(number):  # "1e999" is written well but is no finite number
        raise ValueError(value)
    return number


def empty_values() -> dict:
    """Return the Response answer fields, all empty."""
    return {
        "chosen": "",
        "chosen_position": None,
        "rating": None,
        "number": None,
        "text": "",
        "score": None,
    }


class QuestionType:
    """The behaviour of one question kind; subclasses set the class attributes.

    *kind* is stored in ``Question.kind`` (at most :data:`MAX_KIND_LENGTH` characters) and
    *label* names it in the admin; *template* is the widget the participant page (and
    the admin preview) includes; *export_kind* the tidy format's ``kind`` of its rows, or
    None for a participant attribute (a demographic column), and *scale* what its
    ratings are (``ordinal`` or ``continuous``, the tidy format's ``scale``: the analysis
    picks its models by it); *trial_kinds* the pages that may ask it.
    """

    kind: str = ""
    label: str = ""
    template: str = ""
    export_kind: str | None = None
    scale: str = ""
    trial_kinds: frozenset[str] = frozenset()
    uses_options = False
    is_scale = False
    is_scored = False  # scored against the item's target words (the export's ``target``)
    shows_clips = False  # its answers name a clip the page showed (Shown.clips)
    allows_no_difference = False
    takes_signed_answer = False
    can_be_personal = False
    has_range = False
    # The labelled points a new question of this kind starts with (value, label), for
    # the researcher to reword: none for kinds without options.
    starting_options: tuple[tuple[int, str], ...] = ()

    @property
    def exported_scale(self) -> str:
        """Return the tidy format's ``scale`` of this type's rows: rating rows carry the
        type's scale, every other row none."""
        return self.scale if self.export_kind == "rating" else ""

    def max_length(self, question) -> int:
        """Return the longest text answer *question* takes, in characters."""
        return MAX_PERSONAL_LENGTH if question.is_personal else MAX_TEXT_LENGTH

    def default_options(self, question) -> tuple[tuple[int, str], ...]:
        """Return the labelled points a new *question* starts with (value, label)."""
        return self.starting_options

    def widget(self, question) -> dict:
        """Return what the widget's template needs beyond the question (as ``widget``)."""
        return {}

    def parse(self, question, value: str) -> Answer:
        """Return the posted *value* as an Answer; raise ValueError if it is not one."""
        return Answer(text=value)

    def response_values(self, question, answer: Answer, shown: Shown) -> dict:
        """Check *answer* to *question* on a page that showed *shown*; return the Response
        fields it sets (AnswerRejected if bad)."""
        raise NotImplementedError

    def display(self, question, response) -> str:
        """Return a stored response as the value the page's control holds."""
        return response.text

    def export_value(self, question, response, labels: dict) -> str:
        """Return a stored response as a participant column's value."""
        return self.display(question, response)

    def check(self, question) -> dict[str, str]:
        """Return the question's settings that do not apply to this kind, by field."""
        errors = {}
        if question.allow_no_difference and not self.allows_no_difference:
            errors["allow_no_difference"] = "Only pairwise questions have this answer."
        if question.allow_signed_answer and not self.takes_signed_answer:
            errors["allow_signed_answer"] = "Only open and intelligibility questions take videos."
        if question.is_personal and not self.can_be_personal:
            errors["is_personal"] = "Only short-text questions can hold identifying data."
        return errors


class WholeNumberQuestion(QuestionType):
    """An answer stored as a whole number in Response.rating (scale points, a slider)."""

    def parse(self, question, value: str) -> Answer:
        return Answer(rating=parse_integer(value))

    def display(self, question, response) -> str:
        return "" if response.rating is None else str(response.rating)
