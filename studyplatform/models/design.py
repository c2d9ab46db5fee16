"""Define what participants are asked: questions, blocks and trials (spec 06 "Trial templates").

A *trial* is what one page shows: optionally a clip or a pair of clips, and one or more
questions about it (a comparison page asks one question about a pair; a rating page
asks several Likert questions about one clip; a demographics page asks several
questions about the participant). Responses are keyed by participant × trial × question.
"""

from collections.abc import Iterable

from django.contrib.contenttypes.fields import GenericRelation
from django.core.exceptions import ValidationError
from django.db import models
from django.utils.translation import gettext_lazy as _

from studyplatform.models.items import Item
from studyplatform.models.studies import Condition, Study, check_unlocked, position_field
from studyplatform.questions import QUESTION_TYPES, question_kind_choices, question_type
from studyplatform.questions.base import MAX_KIND_LENGTH


class Question(models.Model):
    """A reusable question within a study; its answer options hold per-point labels."""

    study = models.ForeignKey(
        Study, verbose_name=_("study"), on_delete=models.CASCADE, related_name="questions"
    )
    key = models.SlugField(
        _("key"),
        max_length=60,
        help_text=_("Name used in exported data, e.g. 'naturalness' or 'age'."),
    )
    # The registered question types (studyplatform.questions): a new one needs no migration.
    kind = models.CharField(_("kind"), max_length=MAX_KIND_LENGTH, choices=question_kind_choices)
    text = models.TextField(_("text"), help_text=_("The question as participants read it."))
    help_text = models.TextField(_("help text"), blank=True)
    required = models.BooleanField(_("required"), default=True)
    allow_no_difference = models.BooleanField(
        _("allow 'Cannot see a difference'"),
        default=False,
        help_text=_("Pairwise questions: offer a third answer, 'Cannot see a difference'."),
    )
    no_difference_label = models.CharField(
        _("no difference label"), max_length=100, blank=True, default="Cannot see a difference"
    )
    allow_signed_answer = models.BooleanField(
        _("allow signed answer"),
        default=False,
        help_text=_("Open questions: participants may record a signed answer."),
    )
    is_personal = models.BooleanField(
        _("is personal"),
        default=False,
        help_text=_(
            "Identifying data (name, e-mail): stored apart from responses, never exported."
        ),
    )
    min_value = models.FloatField(
        _("min value"), null=True, blank=True, help_text=_("Number questions: minimum.")
    )
    max_value = models.FloatField(
        _("max value"), null=True, blank=True, help_text=_("Number questions: maximum.")
    )
    position = position_field()

    asl_videos = GenericRelation("studyplatform.AslVideo", verbose_name=_("ASL videos"))

    class Meta:
        verbose_name = _("question")
        verbose_name_plural = _("questions")
        ordering = ["study", "position", "pk"]
        constraints = [
            models.UniqueConstraint(fields=["study", "key"], name="question_key_unique_in_study")
        ]

    def __str__(self) -> str:
        return self.key

    @property
    def type(self):
        """Return this question's type (studyplatform.questions): how answers behave."""
        return question_type(self)

    @property
    def widget(self) -> dict:
        """Return what this question's widget template needs (its type's ``widget``)."""
        return self.type.widget(self)

    @property
    def uses_options(self) -> bool:
        """Return whether answers are one of this question's answer options."""
        return self.type.uses_options

    def clean(self) -> None:
        """Reject settings that do not apply to this kind of question."""
        check_unlocked(self.study if self.study_id else None)
        if self.kind not in QUESTION_TYPES:
            return  # the field's own choices check names it
        errors = self.type.check(self)
        if (
            self.min_value is not None
            and self.max_value is not None
            and self.min_value > self.max_value
        ):
            errors["max_value"] = _("The maximum is below the minimum.")
        if errors:
            raise ValidationError(errors)


class AnswerOption(models.Model):
    """One point of a scale or one option of a choice, with its label."""

    question = models.ForeignKey(
        Question, verbose_name=_("question"), on_delete=models.CASCADE, related_name="options"
    )
    value = models.SmallIntegerField(
        _("value"), help_text=_("Stored and analysed value, e.g. 1–5.")
    )
    label = models.CharField(_("label"), max_length=200, blank=True)
    position = position_field()

    asl_videos = GenericRelation("studyplatform.AslVideo", verbose_name=_("ASL videos"))

    class Meta:
        verbose_name = _("answer option")
        verbose_name_plural = _("answer options")
        ordering = ["question", "position", "value"]
        constraints = [
            models.UniqueConstraint(
                fields=["question", "value"], name="option_value_unique_in_question"
            )
        ]

    def __str__(self) -> str:
        return f"{self.value}: {self.label}" if self.label else str(self.value)

    def clean(self) -> None:
        check_unlocked(self.question.study if self.question_id else None)


class Block(models.Model):
    """A section of the study, shown in order between consent and thank-you."""

    class Kind(models.TextChoices):
        DEMOGRAPHICS = "demographics", _("Demographics")
        INSTRUCTIONS = "instructions", _("Instructions")
        PRACTICE = "practice", _("Practice")
        TRIALS = "trials", _("Trials")
        CLOSING = "closing", _("Closing questions")

    study = models.ForeignKey(
        Study, verbose_name=_("study"), on_delete=models.CASCADE, related_name="blocks"
    )
    key = models.SlugField(_("key"), max_length=60, help_text=_("Name used in exported data."))
    kind = models.CharField(_("kind"), max_length=20, choices=Kind.choices, default=Kind.TRIALS)
    title = models.CharField(_("title"), max_length=200, blank=True)
    intro_text = models.TextField(
        _("intro text"), blank=True, help_text=_("Shown before the block's first page.")
    )
    randomize_order = models.BooleanField(
        _("randomize order"),
        default=False,
        help_text=_("Shuffle the block's pages per participant (seeded)."),
    )
    position = position_field()

    asl_videos = GenericRelation("studyplatform.AslVideo", verbose_name=_("ASL videos"))

    class Meta:
        verbose_name = _("block")
        verbose_name_plural = _("blocks")
        ordering = ["study", "position", "pk"]
        constraints = [
            models.UniqueConstraint(fields=["study", "key"], name="block_key_unique_in_study")
        ]

    def __str__(self) -> str:
        return self.title or self.key

    def clean(self) -> None:
        check_unlocked(self.study if self.study_id else None)


def trial_question_kinds() -> dict[str, frozenset[str]]:
    """Return the question kinds each trial kind may ask (from the question types)."""
    return {
        kind: frozenset(k for k, t in QUESTION_TYPES.items() if kind in t.trial_kinds)
        for kind in Trial.Kind.values
    }


class Trial(models.Model):
    """What one page shows: an optional clip or pair of clips and the questions about it."""

    class Kind(models.TextChoices):
        INFO = "info", _("Information or instructions (no questions)")
        PAIRWISE = "pairwise", _("Pairwise forced choice")
        COMPARATIVE = "comparative", _("Comparative scale")
        RATING = "rating", _("Ratings of one clip")
        INTELLIGIBILITY = "intelligibility", _("Intelligibility")
        OPEN = "open", _("Open questions")
        DEMOGRAPHIC = "demographic", _("Demographic questions")

    TWO_CLIP_KINDS = frozenset({Kind.PAIRWISE, Kind.COMPARATIVE})
    ONE_CLIP_KINDS = frozenset({Kind.RATING, Kind.INTELLIGIBILITY})

    study = models.ForeignKey(
        Study, verbose_name=_("study"), on_delete=models.CASCADE, related_name="trials"
    )
    block = models.ForeignKey(
        Block, verbose_name=_("block"), on_delete=models.CASCADE, related_name="trials"
    )
    key = models.SlugField(_("key"), max_length=80, help_text=_("Name used in exported data."))
    kind = models.CharField(_("kind"), max_length=20, choices=Kind.choices)
    title = models.CharField(_("title"), max_length=200, blank=True)
    text = models.TextField(
        _("text"), blank=True, help_text=_("Text shown on the page above the clips.")
    )
    item = models.ForeignKey(
        Item,
        verbose_name=_("item"),
        on_delete=models.RESTRICT,
        null=True,
        blank=True,
        related_name="trials",
    )
    condition_a = models.ForeignKey(
        Condition,
        verbose_name=_("condition a"),
        on_delete=models.RESTRICT,
        null=True,
        blank=True,
        related_name="+",
        help_text=_("Clip 1 (the only clip of a rating trial; an example clip on an info page)."),
    )
    condition_b = models.ForeignKey(
        Condition,
        verbose_name=_("condition b"),
        on_delete=models.RESTRICT,
        null=True,
        blank=True,
        related_name="+",
        help_text=_("Clip 2 of a pairwise or comparative trial."),
    )
    questions = models.ManyToManyField(
        Question, verbose_name=_("questions"), blank=True, related_name="trials"
    )
    is_attention_check = models.BooleanField(
        _("is attention check"),
        default=False,
        help_text=_("Flag failures in the data (e.g. a pair of identical clips)."),
    )
    expected_answer = models.CharField(
        _("expected answer"),
        max_length=60,
        blank=True,
        help_text=_("Attention checks: the correct answer (a condition key, 'none', or a value)."),
    )
    position = position_field()

    asl_videos = GenericRelation("studyplatform.AslVideo", verbose_name=_("ASL videos"))

    class Meta:
        verbose_name = _("trial")
        verbose_name_plural = _("trials")
        ordering = ["study", "block__position", "position", "pk"]
        constraints = [
            models.UniqueConstraint(fields=["study", "key"], name="trial_key_unique_in_study"),
            models.CheckConstraint(
                condition=models.Q(condition_b__isnull=True)
                | models.Q(kind__in=["pairwise", "comparative"]),
                name="trial_second_clip_only_in_comparisons",
            ),
        ]

    def __str__(self) -> str:
        return self.key

    def clean(self) -> None:
        """Check that the trial's clips suit its kind and belong to its study."""
        check_unlocked(self.study if self.study_id else None)
        errors = {**self._foreign_parts(), **self._clip_problems()}
        if errors:
            raise ValidationError(errors)

    def _foreign_parts(self) -> dict[str, str]:
        """Name the block, item or conditions that belong to another study."""
        errors = {}
        if self.block_id and self.study_id and self.block.study_id != self.study_id:
            errors["block"] = _("The block belongs to another study.")
        for field in ("item", "condition_a", "condition_b"):
            related = getattr(self, field)
            if related is not None and related.study_id != self.study_id:
                errors[field] = _("This belongs to another study.")
        return errors

    def _clip_problems(self) -> dict[str, str]:
        """Name what the trial's kind needs of its item and clips and does not have."""
        errors = {}
        if self.kind in self.TWO_CLIP_KINDS:
            for field in ("item", "condition_a", "condition_b"):
                if getattr(self, field) is None:
                    errors[field] = _("A comparison needs an item and two conditions.")
            same = self.condition_a_id and self.condition_a_id == self.condition_b_id
            if same and not self.is_attention_check:
                errors["condition_b"] = _("Identical clips are only allowed in attention checks.")
        elif self.kind in self.ONE_CLIP_KINDS and (self.item is None or self.condition_a is None):
            errors["item"] = _("This trial needs an item and the condition of its clip.")
        if self.condition_b is not None and self.kind not in self.TWO_CLIP_KINDS:
            errors["condition_b"] = _("Only pairwise and comparative trials show a second clip.")
        return errors

    def check_questions(self, questions: Iterable[Question]) -> None:
        """Raise ValidationError unless *questions* may be asked on this trial."""
        allowed = trial_question_kinds()[self.kind]
        questions = list(questions)
        wrong = [q.key for q in questions if q.kind not in allowed]
        if wrong:
            raise ValidationError(
                _("A %(kind)s trial cannot ask %(questions)s.")
                % {"kind": str(self.get_kind_display()).lower(), "questions": ", ".join(wrong)}
            )
        foreign = [q.key for q in questions if q.study_id != self.study_id]
        if foreign:
            raise ValidationError(
                _("Questions of another study: %(keys)s.") % {"keys": ", ".join(foreign)}
            )
        if self.kind != self.Kind.INFO and not questions:
            raise ValidationError(_("This trial asks no question."))
