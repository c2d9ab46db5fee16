"""Attach ASL videos to participant-facing text (spec 06 "ASL-first")."""

from django.contrib.contenttypes.fields import GenericForeignKey
from django.contrib.contenttypes.models import ContentType
from django.db import models

# The participant-facing text fields of each model, by model name: every one of them
# can carry an ASL video, and the admin lists those that lack one.
PARTICIPANT_FACING_FIELDS: dict[str, tuple[str, ...]] = {
    "study": ("description", "consent_text", "thank_you_text"),
    "block": ("title", "intro_text"),
    "trial": ("title", "text"),
    "question": ("text", "help_text", "no_difference_label"),
    "answeroption": ("label",),
}


class AslVideo(models.Model):
    """An ASL rendering of one text field of a study object (a prompt, a label, consent)."""

    content_type = models.ForeignKey(ContentType, on_delete=models.CASCADE)
    object_id = models.PositiveBigIntegerField()
    target = GenericForeignKey("content_type", "object_id")
    field_name = models.CharField(
        max_length=40, help_text="The text field this video signs, e.g. 'text' or 'consent_text'."
    )
    video = models.FileField(upload_to="asl/")
    poster = models.FileField(upload_to="asl/", blank=True)
    transcript = models.TextField(
        blank=True, help_text="English gloss or caption of the video, if it differs from the text."
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
