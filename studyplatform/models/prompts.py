"""Attach ASL videos to participant-facing text (spec 06 "ASL-first")."""

from django.conf import settings
from django.contrib.contenttypes.fields import GenericForeignKey
from django.contrib.contenttypes.models import ContentType
from django.db import models
from django.utils.translation import gettext
from django.utils.translation import gettext_lazy as _

from studyplatform.files.media_types import ContentValidator

# The participant-facing text fields of each model, by model name: every one of them
# can carry an ASL video, shown before the text, and the admin lists those that lack
# one. Titles are headings, not prompts: the signed intro or instructions carry them.
PARTICIPANT_FACING_FIELDS: dict[str, tuple[str, ...]] = {
    "study": ("description", "consent_text", "thank_you_text"),
    "block": ("intro_text",),
    "trial": ("text",),
    "question": ("text", "help_text", "no_difference_label"),
    "answeroption": ("label",),
}


def _video_field() -> models.FileField:
    """Return the field of a signed text's video: checked by content, stored as what it is."""
    return models.FileField(
        _("video"),
        upload_to="asl/",
        validators=[ContentValidator("video")],
        help_text=_("An MP4 or WebM video (checked by its content)."),
    )


def _poster_field() -> models.FileField:
    return models.FileField(
        _("poster"),
        upload_to="asl/",
        blank=True,
        validators=[ContentValidator("image")],
        help_text=_("Optional: a PNG, JPEG or WebP still."),
    )


class AslVideo(models.Model):
    """An ASL rendering of one text field of a study object (a prompt, a label, consent)."""

    content_type = models.ForeignKey(
        ContentType, verbose_name=_("content type"), on_delete=models.CASCADE
    )
    object_id = models.PositiveBigIntegerField(_("object id"))
    target = GenericForeignKey("content_type", "object_id")
    field_name = models.CharField(
        _("field name"),
        max_length=40,
        help_text=_("The text field this video signs, e.g. 'text' or 'consent_text'."),
    )
    video = _video_field()
    poster = _poster_field()
    transcript = models.TextField(
        _("transcript"),
        blank=True,
        help_text=_("English gloss or caption of the video, if it differs from the text."),
    )
    credit = models.CharField(
        _("credit"),
        max_length=200,
        blank=True,
        help_text=_(
            "Who or what signs the video, shown under it in every language setting "
            "(e.g. “Signed by …”, or “Avatar-signed demo material”)."
        ),
    )
    created_at = models.DateTimeField(_("created at"), auto_now_add=True)

    class Meta:
        verbose_name_plural = _("ASL videos")
        verbose_name = _("ASL video")
        constraints = [
            models.UniqueConstraint(
                fields=["content_type", "object_id", "field_name"],
                name="one_asl_video_per_text",
            )
        ]
        indexes = [models.Index(fields=["content_type", "object_id"])]

    def __str__(self) -> str:
        return gettext("ASL for %(model)s #%(id)s %(field)s") % {
            "model": self.content_type.model,
            "id": self.object_id,
            "field": self.field_name,
        }


class SignedTemplate(models.Model):
    """A signed text a researcher records once and attaches to many studies.

    Consent, instructions and thank-you templates sign those texts wherever a study has
    no video of its own for them; the button templates sign what Next, Previous, Play
    and Replay do, next to the buttons.
    """

    class Kind(models.TextChoices):
        CONSENT = "consent", _("Consent")
        INSTRUCTIONS = "instructions", _("Instructions")
        THANK_YOU = "thank_you", _("Thank you")
        NEXT = "next", _("“Next” button")
        PREVIOUS = "previous", _("“Previous” button")
        PLAY = "play", _("“Play” / “Replay” buttons")

    owner = models.ForeignKey(
        settings.AUTH_USER_MODEL,
        verbose_name=_("owner"),
        on_delete=models.CASCADE,
        related_name="signed_templates",
    )
    kind = models.CharField(_("kind"), max_length=20, choices=Kind.choices)
    name = models.CharField(
        _("name"), max_length=100, help_text=_("How you find it, e.g. 'Consent (lab)'.")
    )
    video = _video_field()
    poster = _poster_field()
    transcript = models.TextField(
        _("transcript"),
        blank=True,
        help_text=_("What the video signs, in English (shown as its caption)."),
    )
    created_at = models.DateTimeField(_("created at"), auto_now_add=True)

    class Meta:
        verbose_name = _("signed template")
        verbose_name_plural = _("signed templates")
        ordering = ["kind", "name", "pk"]

    def __str__(self) -> str:
        return f"{self.name} ({self.get_kind_display()})"
