"""Record that a participant's data was deleted: the audit trail of withdrawals."""

from django.conf import settings
from django.db import models
from django.utils.translation import gettext_lazy as _

from studyplatform.models.studies import Study


class Withdrawal(models.Model):
    """A participant who withdrew: what was deleted, when and by whom; nothing personal."""

    study = models.ForeignKey(
        Study, verbose_name=_("study"), on_delete=models.CASCADE, related_name="withdrawals"
    )
    participant_number = models.PositiveBigIntegerField(
        _("participant number"),
        help_text=_("The number the participant had (their data, token and links are gone)."),
    )
    withdrawn_at = models.DateTimeField(_("withdrawn at"), auto_now_add=True)
    withdrawn_by = models.ForeignKey(
        settings.AUTH_USER_MODEL,
        verbose_name=_("withdrawn by"),
        on_delete=models.SET_NULL,
        null=True,
        blank=True,
        related_name="+",
        help_text=_("The researcher who carried it out; empty: the participant."),
    )
    reason = models.CharField(_("reason"), max_length=200, blank=True)
    responses = models.PositiveIntegerField(_("responses"), default=0)
    events = models.PositiveIntegerField(_("events"), default=0)
    personal_answers = models.PositiveIntegerField(_("personal answers"), default=0)
    files = models.PositiveIntegerField(
        _("files"), default=0, help_text=_("Signed-answer videos deleted.")
    )

    class Meta:
        verbose_name = _("withdrawal")
        verbose_name_plural = _("withdrawals")
        ordering = ["-withdrawn_at"]

    def __str__(self) -> str:
        return f"participant {self.participant_number} withdrew from {self.study}"
