"""Record who takes a study, how they arrived and what schedule they were given."""

import secrets

from django.db import models

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
        ASL_ENGLISH = "asl_en", "ASL and English"
        ENGLISH = "en", "English only"

    study = models.ForeignKey(Study, on_delete=models.PROTECT, related_name="participants")
    token = models.CharField(
        max_length=64, unique=True, default=new_participant_token, editable=False
    )
    recruitment_params = models.JSONField(
        default=dict,
        blank=True,
        help_text="URL parameters the participant arrived with (e.g. PROLIFIC_PID).",
    )
    seed = models.BigIntegerField(
        default=new_randomization_seed, help_text="Seed of this participant's randomization."
    )
    schedule = models.JSONField(
        default=list, blank=True, help_text="The exact sequence of pages this participant saw."
    )
    language = models.CharField(
        max_length=10, choices=Language.choices, default=Language.ASL_ENGLISH
    )
    is_pilot = models.BooleanField(
        default=False, help_text="Joined while the study was in pilot; excluded from analysis."
    )
    position = models.PositiveIntegerField(
        default=0,
        help_text="Page the participant is on: 0 before consent, 1..n the scheduled pages.",
    )
    reached = models.PositiveIntegerField(
        default=0, help_text="Furthest page the participant reached (they may go back)."
    )

    class Review(models.TextChoices):
        PENDING = "pending", "Not reviewed"
        APPROVED = "approved", "Approved"
        REJECTED = "rejected", "Rejected (excluded from analysis)"

    review = models.CharField(
        max_length=10,
        choices=Review.choices,
        default=Review.PENDING,
        db_index=True,
        help_text="The researcher's decision; rejected participants are flagged 'excluded'.",
    )
    completion_code = models.CharField(
        max_length=80, blank=True, help_text="The code this participant was shown at the end."
    )
    user_agent = models.CharField(max_length=400, blank=True)
    started_at = models.DateTimeField(auto_now_add=True)
    consented_at = models.DateTimeField(null=True, blank=True)
    last_seen_at = models.DateTimeField(null=True, blank=True)
    finished_at = models.DateTimeField(null=True, blank=True, db_index=True)

    class Meta:
        ordering = ["study", "started_at", "pk"]

    def __str__(self) -> str:
        return f"Participant {self.pk} of {self.study.slug}"

    @property
    def is_finished(self) -> bool:
        """Return whether the participant reached the end of the study."""
        return self.finished_at is not None


class PersonalAnswer(models.Model):
    """An identifying answer (name, e-mail), kept apart from responses and never exported."""

    participant = models.ForeignKey(
        Participant, on_delete=models.CASCADE, related_name="personal_answers"
    )
    question = models.ForeignKey(Question, on_delete=models.RESTRICT, related_name="+")
    value = models.CharField(max_length=300)

    class Meta:
        constraints = [
            models.UniqueConstraint(
                fields=["participant", "question"], name="one_personal_answer_per_question"
            )
        ]

    def __str__(self) -> str:
        return f"{self.question.key} of participant {self.participant_id}"
