"""Attach ASL videos to participant-facing text (spec 06 "ASL-first")."""

from django.conf import settings
from django.contrib.contenttypes.fields import GenericForeignKey
from django.contrib.contenttypes.models import ContentType
from django.db import models

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
        upload_to="asl/",
        validators=[ContentValidator("video")],
        help_text="An MP4 or WebM video (checked by its content).",
    )


def _poster_field() -> models.FileField:
    return models.FileField(
        upload_to="asl/",
        blank=True,
        validators=[ContentValidator("image")],
        help_text="Optional: a PNG, JPEG or WebP still.",
    )


class AslVideo(models.Model):
    """An ASL rendering of one text field of a study object (a prompt, a label, consent)."""

    content_type = models.ForeignKey(ContentType, on_delete=models.CASCADE)
    object_id = models.PositiveBigIntegerField()
    target = GenericForeignKey("content_type", "object_id")
    field_name = models.CharField(
        max_length=40, help_text="The text field this video signs, e.g. 'text' or 'consent_text'."
    )
    video = _video_field()
    poster = _poster_field()
    transcript = models.TextField(
        blank=True, help_text="English gloss or caption of the video, if it differs from the text."
    )
    credit = models.CharField(
        max_length=200,
        blank=True,
        help_text="Who or what signs the video, shown under it in every language setting "
        "(e.g. “Signed by …”, or “Avatar-signed demo material”).",
    )
    created_at = models.DateTimeField(auto_now_add=True)

    class Meta:
        verbose_name = "ASL video"
        constraints = [
            models.UniqueConstraint(
                fields=["content_type", "object_id", "field_name"],
                name="one_asl_video_per_text",
            )
        ]
        indexes = [models.Index(fields=["content_type", "object_id"])]

    def __str__(self) -> str:
        return f"ASL for {self.content_type.model} #{self.object_id} {self.field_name}"


class SignedTemplate(models.Model):
    """A signed text a researcher records once and attaches to many studies.

    Consent, instructions and thank-you templates sign those texts wherever a study has
    no video of its own for them; the button templates sign what Next, Previous, Play
    and Replay do, next to the buttons.
    """

    class Kind(models.TextChoices):
        CONSENT = "consent", "Consent"
        INSTRUCTIONS = "instructions", "Instructions"
        THANK_YOU = "thank_you", "Thank you"
        NEXT = "next", "“Next” button"
        PREVIOUS = "previous", "“Previous” button"
        PLAY = "play", "“Play” / “Replay” buttons"

    owner = models.ForeignKey(
        settings.AUTH_USER_MODEL, on_delete=models.CASCADE, related_name="signed_templates"
    )
    kind = models.CharField(max_length=20, choices=Kind.choices)
    name = models.CharField(max_length=100, help_text="How you find it, e.g. 'Consent (lab)'.")
    video = _video_field()
    poster = _poster_field()
    transcript = models.TextField(
        blank=True, help_text="What the video signs, in English (shown as its caption)."
    )
    created_at = models.DateTimeField(auto_now_add=True)

    class Meta:
        ordering = ["kind", "name", "pk"]

    def __str__(self) -> str:
        return f"{self.name} ({self.get_kind_display()})"
