"""Record that a participant's data was deleted: the audit trail of withdrawals."""

from django.conf import settings
from django.db import models

from studyplatform.models.studies import Study


class Withdrawal(models.Model):
    """A participant who withdrew: what was deleted, when and by whom; nothing personal."""

    study = models.ForeignKey(Study, on_delete=models.CASCADE, related_name="withdrawals")
    participant_number = models.PositiveBigIntegerField(
        help_text="The number the participant had (their data, token and links are gone)."
    )
    withdrawn_at = models.DateTimeField(auto_now_add=True)
    withdrawn_by = models.ForeignKey(
        settings.AUTH_USER_MODEL,
        on_delete=models.SET_NULL,
        null=True,
        blank=True,
        related_name="+",
        help_text="The researcher who carried it out; empty: the participant.",
    )
    reason = models.CharField(max_length=200, blank=True)
    responses = models.PositiveIntegerField(default=0)
    events = models.PositiveIntegerField(default=0)
    personal_answers = models.PositiveIntegerField(default=0)
    files = models.PositiveIntegerField(default=0, help_text="Signed-answer videos deleted.")

    class Meta:
        ordering = ["-withdrawn_at"]

    def __str__(self) -> str:
        return f"participant {self.participant_number} withdrew from {self.study}"
