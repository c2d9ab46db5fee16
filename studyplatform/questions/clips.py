"""Questions about the clips on the page: which of two is better (pairwise forced choice)."""

from django.utils.translation import gettext, gettext_lazy

from studyplatform.questions.base import (
    NO_DIFFERENCE,
    Answer,
    AnswerRejected,
    QuestionType,
    empty_values,
    parse_integer,
)


class PairwiseQuestion(QuestionType):
    """Clip 1 or Clip 2 (or "Cannot see a difference"); stored as the chosen condition."""

    kind = "pairwise"
    label = gettext_lazy("Pairwise forced choice (Clip 1 / Clip 2)")
    shows_clips = True
    template = "studyplatform/questions/pairwise.html"
    export_kind = "pairwise"
    trial_kinds = frozenset({"pairwise"})
    allows_no_difference = True

    def parse(self, question, value: str) -> Answer:
        return Answer(choice_position=parse_integer(value))

    def response_values(self, question, answer, shown) -> dict:
        values, position = empty_values(), answer.choice_position
        if position == 0 and question.allow_no_difference:
            values["chosen"] = NO_DIFFERENCE
        elif position in (1, 2):
            values["chosen"] = shown.clips[position - 1].key
            values["chosen_position"] = position
        else:
            raise AnswerRejected(
                gettext("“%(value)s” is not one of the clips on this page.") % {"value": position}
            )
        return values

    def display(self, question, response) -> str:
        return str(response.chosen_position or 0) if response.chosen else ""
