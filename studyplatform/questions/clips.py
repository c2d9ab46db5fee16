"""Questions about the clips on the page: which of two is better (pairwise forced choice)."""

from studyplatform.questions.base import (
    Answer,
    AnswerRejected,
    QuestionType,
    empty_values,
    parse_integer,
)


class PairwiseQuestion(QuestionType):
    """Clip 1 or Clip 2 (or "Cannot see a difference"); stored as the chosen condition."""

    kind = "pairwise"
    template = "studyplatform/questions/pairwise.html"
    export_kind = "pairwise"
    trial_kinds = frozenset({"pairwise"})
    allows_no_difference = True

    def parse(self, question, value: str) -> Answer:
        return Answer(choice_position=parse_integer(value))

    def response_values(self, question, answer, participant, trial) -> dict:
        from studyplatform.lib.presentation import presented_conditions
        from studyplatform.models import Response

        values, position = empty_values(), answer.choice_position
        if position == 0 and question.allow_no_difference:
            values["chosen"] = Response.NO_DIFFERENCE
        elif position in (1, 2):
            clips = presented_conditions(participant, trial)
            values["chosen"] = clips[position - 1].key
            values["chosen_position"] = position
        else:
            raise AnswerRejected(f"“{position}” is not one of the clips on this page.")
        return values

    def display(self, question, response) -> str:
        return str(response.chosen_position or 0) if response.chosen else ""
