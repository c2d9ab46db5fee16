"""Record who takes a study, how they arrived and what schedule they were given."""

import secrets

from django.db import models
from django.utils.translation import gettext
from django.utils.translation import gettext_lazy as _

from studyplatform.models.design import Question
from studyplatform.models.studies import Study

# Where a browser's session remembers its participants: {study slug: token}.
PARTICIPANT_SESSION_KEY = "signstudy_participants"


def new_participant_token() -> str:
    """Return a random, unguessable participant token (256 bits, URL-safe)."""
    return secrets.token_urlsafe(32)


def new_randomization_seed() -> int:
    """Return a random seed for a participant's schedule (fits a signed 64-bit column)."""
    return secrets.randbits(63)


class Participant(models.Model):
    """One person's session in a study, reachable only through its token."""

    class Language(models.TextChoices):
        ASL_ENGLISH = "asl_en", _("ASL and English")
        ENGLISH = "en", _("English only")

    study = models.ForeignKey(
        Study, verbose_name=_("study"), on_delete=models.PROTECT, related_name="participants"
    )
    token = models.CharField(
        _("token"), max_length=64, unique=True, default=new_participant_token, editable=False
    )
    recruitment_params = models.JSONField(
        _("recruitment params"),
        default=dict,
        blank=True,
        help_text=_("URL parameters the participant arrived with (e.g. PROLIFIC_PID)."),
    )
    seed = models.BigIntegerField(
        _("seed"),
        default=new_randomization_seed,
        help_text=_("Seed of this participant's randomization."),
    )
    schedule = models.JSONField(
        _("schedule"),
        default=list,
        blank=True,
        help_text=_("The exact sequence of pages this participant saw."),
    )
    language = models.CharField(
        _("language"), max_length=10, choices=Language.choices, default=Language.ASL_ENGLISH
    )
    is_pilot = models.BooleanField(
        _("is pilot"),
        default=False,
        help_text=_("Joined while the study was in pilot; excluded from analysis."),
    )
    position = models.PositiveIntegerField(
        _("position"),
        default=0,
        help_text=_("Page the participant is on: 0 before consent, 1..n the scheduled pages."),
    )
    reached = models.PositiveIntegerField(
        _("reached"),
        default=0,
        help_text=_("Furthest page the participant reached (they may go back)."),
    )

    class Review(models.TextChoices):
        PENDING = "pending", _("Not reviewed")
        APPROVED = "approved", _("Approved")
        REJECTED = "rejected", _("Rejected (excluded from analysis)")

    review = models.CharField(
        _("review"),
        max_length=10,
        choices=Review.choices,
        default=Review.PENDING,
        db_index=True,
        help_text=_("The researcher's decision; rejected participants are flagged 'excluded'."),
    )
    completion_code = models.CharField(
        _("completion code"),
        max_length=80,
        blank=True,
        help_text=_("The code this participant was shown at the end."),
    )
    user_agent = models.CharField(_("user agent"), max_length=400, blank=True)
    started_at = models.DateTimeField(_("started at"), auto_now_add=True)
    consented_at = models.DateTimeField(_("consented at"), null=True, blank=True)
    last_seen_at = models.DateTimeField(_("last seen at"), null=True, blank=True)
    finished_at = models.DateTimeField(_("finished at"), null=True, blank=True, db_index=True)

    class Meta:
        verbose_name = _("participant")
        verbose_name_plural = _("participants")
        ordering = ["study", "started_at", "pk"]

    def __str__(self) -> str:
        return gettext("Participant %(number)s of %(study)s") % {
            "number": self.pk,
            "study": self.study.slug,
        }

    @property
    def is_finished(self) -> bool:
        """Return whether the participant reached the end of the study."""
        return self.finished_at is not None


class PersonalAnswer(models.Model):
    """An identifying answer (name, e-mail), kept apart from responses and never exported."""

    participant = models.ForeignKey(
        Participant,
        verbose_name=_("participant"),
        on_delete=models.CASCADE,
        related_name="personal_answers",
    )
    question = models.ForeignKey(
        Question, verbose_name=_("question"), on_delete=models.RESTRICT, related_name="+"
    )
    value = models.CharField(_("value"), max_length=300)

    class Meta:
        verbose_name = _("personal answer")
        verbose_name_plural = _("personal answers")
        constraints = [
            models.UniqueConstraint(
                fields=["participant", "question"], name="one_personal_answer_per_question"
            )
        ]

    def __str__(self) -> str:
        return gettext("%(question)s of participant %(number)s") % {
            "question": self.question.key,
            "number": self.participant_id,
        }
