"""A continuous rating: a slider between two labelled ends, which starts untouched."""

from django.utils.translation import gettext, gettext_lazy

from studyplatform.questions.base import (
    AnswerRejected,
    WholeNumberQuestion,
    empty_values,
)

# The range of a slider whose question sets none (a visual analogue scale's 0–100), and
# the widest any may have: answers are stored in Response.rating, a small integer.
DEFAULT_RANGE = (0, 100)
LIMITS = (-32768, 32767)


def slider_range(question) -> tuple[int, int]:
    """Return the whole-number range of a slider question, its own or 0–100."""
    low = DEFAULT_RANGE[0] if question.min_value is None else question.min_value
    high = DEFAULT_RANGE[1] if question.max_value is None else question.max_value
    return int(low), int(high)


class SliderQuestion(WholeNumberQuestion):
    """A rating of one clip on a slider, analysed as continuous (a linear model).

    The page's slider has no value until the participant moves or taps it: an untouched
    slider sends nothing, so a required one is caught like any unanswered question
    instead of being saved at its starting point. Answer options, if any, label points
    of the range (usually its two ends).
    """

    kind = "slider"
    label = gettext_lazy("Slider rating (continuous)")
    template = "studyplatform/questions/slider.html"
    export_kind = "rating"
    scale = "continuous"
    trial_kinds = frozenset({"rating"})
    uses_options = True
    has_range = True

    def default_options(self, question) -> tuple[tuple[int, str], ...]:
        low, high = slider_range(question)
        return ((low, "Not at all"), (high, "Completely"))

    def widget(self, question) -> dict:
        low, high = slider_range(question)
        return {"low": low, "high": high, "start": (low + high) // 2}

    def response_values(self, question, answer, shown) -> dict:
        low, high = slider_range(question)
        if answer.rating is None or not low <= answer.rating <= high:
            raise AnswerRejected(
                gettext(
                    "“%(value)s” is outside the slider of “%(question)s” (%(low)s to %(high)s)."
                )
                % {"value": answer.rating, "question": question.key, "low": low, "high": high}
            )
        return {**empty_values(), "rating": answer.rating}

    def check(self, question) -> dict[str, str]:
        errors = super().check(question)
        for field in ("min_value", "max_value"):
            value = getattr(question, field)
            if value is not None and not (LIMITS[0] <= value <= LIMITS[1] and value == int(value)):
                errors[field] = (
                    f"A slider's ends are whole numbers from {LIMITS[0]} to {LIMITS[1]}."
                )
        if errors.keys() & {"min_value", "max_value"}:
            return errors
        low, high = slider_range(question)
        if low >= high:
            errors["max_value"] = "A slider's maximum must be above its minimum."
        return errors
