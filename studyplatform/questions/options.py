"""Questions answered with one of their answer options: scales and single choices."""

from django.utils.translation import gettext, gettext_lazy

from studyplatform.questions.base import (
    AnswerRejected,
    WholeNumberQuestion,
    empty_values,
)


class OptionsQuestion(WholeNumberQuestion):
    """An answer that is the value of one of the question's options."""

    template = "studyplatform/questions/options.html"
    uses_options = True
    is_scale = True
    scale = "ordinal"

    def response_values(self, question, answer, shown) -> dict:
        allowed = {option.value for option in question.options.all()}
        if answer.rating not in allowed:
            raise AnswerRejected(
                gettext("“%(value)s” is not a point of the scale of “%(question)s”.")
                % {"value": answer.rating, "question": question.key}
            )
        return {**empty_values(), "rating": answer.rating}

    def export_value(self, question, response, labels: dict) -> str:
        return labels.get((question.pk, response.rating), str(response.rating))


class ComparativeQuestion(OptionsQuestion):
    """A 5-point scale between two clips (Clip 1 a lot better … Clip 2 a lot better)."""

    kind = "comparative"
    label = gettext_lazy("Comparative scale between two clips")
    starting_options = tuple(
        enumerate(
            (
                "Clip 1 a lot better",
                "Clip 1 a little better",
                "Both the same",
                "Clip 2 a little better",
                "Clip 2 a lot better",
            ),
            1,
        )
    )
    export_kind = "comparative"
    trial_kinds = frozenset({"comparative"})


class LikertQuestion(OptionsQuestion):
    """A Likert rating of one clip, with a label per point."""

    kind = "likert"
    label = gettext_lazy("Likert rating")
    starting_options = tuple(
        enumerate(("Not at all", "Slightly", "Moderately", "Very", "Extremely"), 1)
    )
    export_kind = "rating"
    trial_kinds = frozenset({"rating"})


class ChoiceQuestion(OptionsQuestion):
    """A single choice about the participant (a demographic column)."""

    kind = "choice"
    label = gettext_lazy("Single choice (demographic)")
    trial_kinds = frozenset({"demographic"})
    is_scale = False
    scale = ""
