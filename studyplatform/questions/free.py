"""Questions answered in the participant's own words or numbers."""

from django.utils.translation import gettext, gettext_lazy

from studyplatform.questions.base import (
    Answer,
    AnswerRejected,
    QuestionType,
    empty_values,
    parse_number,
)


class NumberQuestion(QuestionType):
    """A number within the question's range (a demographic column)."""

    kind = "number"
    label = gettext_lazy("Number (demographic)")
    template = "studyplatform/questions/number.html"
    trial_kinds = frozenset({"demographic"})
    has_range = True

    def parse(self, question, value: str) -> Answer:
        return Answer(number=parse_number(value.strip()))

    def response_values(self, question, answer, shown) -> dict:
        number = answer.number
        if number is None or number != number:
            raise AnswerRejected(
                gettext("“%(question)s” needs a number.") % {"question": question.key}
            )
        if (question.min_value is not None and number < question.min_value) or (
            question.max_value is not None and number > question.max_value
        ):
            low = "−∞" if question.min_value is None else f"{question.min_value:g}"
            high = "∞" if question.max_value is None else f"{question.max_value:g}"
            raise AnswerRejected(
                gettext("%(number)s is outside the allowed range %(low)s to %(high)s.")
                % {"number": f"{number:g}", "low": low, "high": high}
            )
        return {**empty_values(), "number": number}

    def display(self, question, response) -> str:
        return "" if response.number is None else f"{response.number:g}"


class TextQuestion(QuestionType):
    """Free text, stripped and bounded."""

    template = "studyplatform/questions/text.html"

    def response_values(self, question, answer, shown) -> dict:
        text, limit = answer.text.strip(), self.max_length(question)
        if len(text) > limit:
            raise AnswerRejected(
                gettext("The answer is longer than %(limit)s characters.") % {"limit": f"{limit:,}"}
            )
        if not text and question.required:
            raise AnswerRejected(
                gettext("“%(question)s” needs an answer.") % {"question": question.key}
            )
        return {**empty_values(), "text": text}


class ShortTextQuestion(TextQuestion):
    """A short text about the participant; identifying ones (name, e-mail) stay apart."""

    kind = "short_text"
    label = gettext_lazy("Short text (demographic)")
    template = "studyplatform/questions/short_text.html"
    trial_kinds = frozenset({"demographic"})
    can_be_personal = True


class EmailQuestion(ShortTextQuestion):
    """An e-mail address (checked like Django's EmailValidator); usually personal."""

    kind = "email"
    label = gettext_lazy("E-mail address (demographic, usually personal)")
    template = "studyplatform/questions/email.html"

    def response_values(self, question, answer, shown) -> dict:
        from django.core.exceptions import ValidationError
        from django.core.validators import validate_email

        values = super().response_values(question, answer, shown)
        if values["text"]:
            try:
                validate_email(values["text"])
            except ValidationError:
                raise AnswerRejected(
                    gettext("“%(text)s” is not an e-mail address (like name@example.org).")
                    % {"text": values["text"][:60]}
                ) from None
        return values


class OpenQuestion(TextQuestion):
    """An open question, answered in writing or signed on camera."""

    kind = "open"
    label = gettext_lazy("Open question")
    export_kind = "text"
    trial_kinds = frozenset({"open"})
    takes_signed_answer = True


class IntelligibilityQuestion(OpenQuestion):
    """ "What is the signer saying?": free text scored against the item's target words."""

    kind = "intelligibility"
    label = gettext_lazy("Intelligibility (free text, scored)")
    trial_kinds = frozenset({"intelligibility"})
    is_scored = True

    def response_values(self, question, answer, shown) -> dict:
        from analysis.intelligibility import word_accuracy

        values = super().response_values(question, answer, shown)
        if shown.scoring_target and values["text"]:
            score = word_accuracy(values["text"], shown.scoring_target)
            values["score"] = None if score != score else score
        return values
