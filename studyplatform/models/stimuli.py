"""Record the rendered clips of a study and the parameters that produced them."""

from django.db import models

from studyplatform.models.studies import Condition, Item


class Stimulus(models.Model):
    """One rendered clip: a condition applied to an item, with its poster frame."""

    class Status(models.TextChoices):
        PENDING = "pending", "Pending"
        RENDERING = "rendering", "Rendering"
        READY = "ready", "Ready"
        FAILED = "failed", "Failed"

    condition = models.ForeignKey(Condition, on_delete=models.CASCADE, related_name="stimuli")
    item = models.ForeignKey(Item, on_delete=models.CASCADE, related_name="stimuli")
    content_hash = models.CharField(
        max_length=64,
        db_index=True,
        help_text="Hash of everything that determines the clip's pixels (its file name); "
        "studies that show the same clip share the file.",
    )
    status = models.CharField(
        max_length=10, choices=Status.choices, default=Status.PENDING, db_index=True
    )
    error = models.TextField(blank=True)
    video = models.FileField(upload_to="stimuli/", blank=True)
    poster = models.FileField(upload_to="stimuli/", blank=True)
    parameters = models.JSONField(
        default=dict, blank=True, help_text="Synthesis parameters the clip was rendered with."
    )
    engine_version = models.CharField(max_length=40, blank=True)
    duration_ms = models.PositiveIntegerField(null=True, blank=True)
    frame_count = models.PositiveIntegerField(null=True, blank=True)
    width = models.PositiveSmallIntegerField(null=True, blank=True)
    height = models.PositiveSmallIntegerField(null=True, blank=True)
    size_bytes = models.PositiveBigIntegerField(null=True, blank=True)
    sha256 = models.CharField("SHA-256 of the video file", max_length=64, blank=True)
    created_at = models.DateTimeField(auto_now_add=True)
    rendered_at = models.DateTimeField(null=True, blank=True)

    class Meta:
        verbose_name_plural = "stimuli"
        ordering = ["condition__study", "item__position", "condition__position", "pk"]
        indexes = [models.Index(fields=["condition", "item"])]

    def __str__(self) -> str:
        return f"{self.item.key} · {self.condition}"
