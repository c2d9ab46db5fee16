"""Record a study's clips: rendered ones with the parameters that produced them, and
the files researchers upload for conditions whose clips they bring."""

from django.db import models
from django.urls import reverse
from django.utils.translation import gettext_lazy as _

from studyplatform.files.storage import private_storage
from studyplatform.models.items import Item
from studyplatform.models.studies import Condition


class UploadedClip(models.Model):
    """A researcher's video of one item in a condition of uploaded clips.

    Stored in private media under its SHA-256 as a browser plays it (H.264 MP4 with
    faststart, or WebM), with a poster frame; served to participants only while its
    study takes participants (:func:`studyplatform.views.uploaded_clip`).
    """

    condition = models.ForeignKey(
        Condition, verbose_name=_("condition"), on_delete=models.CASCADE, related_name="uploads"
    )
    item = models.ForeignKey(
        Item, verbose_name=_("item"), on_delete=models.CASCADE, related_name="uploads"
    )
    video = models.FileField(_("video"), upload_to="uploads/", storage=private_storage)
    poster = models.FileField(_("poster"), upload_to="uploads/", storage=private_storage)
    original_name = models.CharField(
        _("original name"), max_length=255, help_text=_("The file's name as uploaded.")
    )
    source_sha256 = models.CharField(
        _("SHA-256 of the file as uploaded"),
        max_length=64,
        help_text=_("Differs from the stored file's when it was converted for browsers."),
    )
    sha256 = models.CharField(_("SHA-256 of the stored video"), max_length=64, db_index=True)
    source_codec = models.CharField(_("source codec"), max_length=40, blank=True)
    converted = models.CharField(
        _("converted"),
        max_length=20,
        blank=True,
        help_text=_(
            "How the upload was made playable: '' kept as it came, 'remuxed' "
            "(frames copied into a browser's container), 'transcoded' (re-encoded as H.264)."
        ),
    )
    duration_ms = models.PositiveIntegerField(_("duration ms"))
    frame_count = models.PositiveIntegerField(_("frame count"))
    frame_rate = models.FloatField(_("frame rate"))
    width = models.PositiveSmallIntegerField(_("width"))
    height = models.PositiveSmallIntegerField(_("height"))
    size_bytes = models.PositiveBigIntegerField(_("size bytes"))
    uploaded_at = models.DateTimeField(_("uploaded at"), auto_now=True)

    class Meta:
        verbose_name = _("uploaded clip")
        verbose_name_plural = _("uploaded clips")
        ordering = ["condition", "item__position", "pk"]
        constraints = [
            models.UniqueConstraint(fields=["condition", "item"], name="one_upload_per_clip")
        ]

    def __str__(self) -> str:
        return f"{self.item.key} · {self.condition}: {self.original_name}"


class Stimulus(models.Model):
    """One rendered clip: a condition applied to an item, with its poster frame."""

    class Status(models.TextChoices):
        PENDING = "pending", _("Pending")
        RENDERING = "rendering", _("Rendering")
        READY = "ready", _("Ready")
        FAILED = "failed", _("Failed")
        MISSING = "missing", _("Not uploaded yet")

    condition = models.ForeignKey(
        Condition, verbose_name=_("condition"), on_delete=models.CASCADE, related_name="stimuli"
    )
    item = models.ForeignKey(
        Item, verbose_name=_("item"), on_delete=models.CASCADE, related_name="stimuli"
    )
    content_hash = models.CharField(
        _("content hash"),
        max_length=64,
        db_index=True,
        help_text=_(
            "Hash of everything that determines the clip's pixels (its file name); "
            "studies that show the same clip share the file."
        ),
    )
    status = models.CharField(
        _("status"), max_length=10, choices=Status.choices, default=Status.PENDING, db_index=True
    )
    error = models.TextField(_("error"), blank=True)
    video = models.FileField(_("video"), upload_to="stimuli/", blank=True)
    poster = models.FileField(_("poster"), upload_to="stimuli/", blank=True)
    parameters = models.JSONField(
        _("parameters"),
        default=dict,
        blank=True,
        help_text=_("Synthesis parameters the clip was rendered with."),
    )
    engine_version = models.CharField(_("engine version"), max_length=40, blank=True)
    duration_ms = models.PositiveIntegerField(_("duration ms"), null=True, blank=True)
    frame_count = models.PositiveIntegerField(_("frame count"), null=True, blank=True)
    width = models.PositiveSmallIntegerField(_("width"), null=True, blank=True)
    height = models.PositiveSmallIntegerField(_("height"), null=True, blank=True)
    size_bytes = models.PositiveBigIntegerField(_("size bytes"), null=True, blank=True)
    sha256 = models.CharField(_("SHA-256 of the video file"), max_length=64, blank=True)
    upload = models.ForeignKey(
        UploadedClip,
        verbose_name=_("upload"),
        on_delete=models.SET_NULL,
        null=True,
        blank=True,
        related_name="+",
        help_text=_("The uploaded file this clip is (conditions of uploaded clips only)."),
    )
    created_at = models.DateTimeField(_("created at"), auto_now_add=True)
    rendered_at = models.DateTimeField(_("rendered at"), null=True, blank=True)

    class Meta:
        verbose_name = _("stimulus")
        verbose_name_plural = _("stimuli")
        ordering = ["condition__study", "item__position", "condition__position", "pk"]
        indexes = [models.Index(fields=["condition", "item"])]

    def __str__(self) -> str:
        return f"{self.item.key} · {self.condition}"

    @property
    def video_url(self) -> str:
        """Return where browsers fetch the clip ("" before it exists)."""
        if self.upload is not None:
            return reverse("uploaded_clip", args=[self.upload.video.name])
        return self.video.url if self.video else ""

    @property
    def poster_url(self) -> str:
        """Return where browsers fetch the clip's poster frame ("" if it has none)."""
        if self.upload is not None:
            return reverse("uploaded_clip", args=[self.upload.poster.name])
        return self.poster.url if self.poster else ""


class ClipUpload(models.Model):
    """A researcher's upload of clips being made playable in the background: one video
    of an item in a condition, or a zip whose manifest names many.

    The request checks what it can at once (the target, the size, that a video is a
    video by its content, a zip's manifest and members) and keeps the file under
    ``incoming/``; a job decodes and converts it (issue 51: a conversion held a web
    request for as long as ffmpeg took, a zip's 2,000 clips one after another).
    """

    class Status(models.TextChoices):
        QUEUED = "queued", _("Waiting to be converted")
        CONVERTING = "converting", _("Converting")
        DONE = "done", _("Saved")
        FAILED = "failed", _("Nothing saved")

    study = models.ForeignKey(
        "studyplatform.Study",
        verbose_name=_("study"),
        on_delete=models.CASCADE,
        related_name="clip_uploads",
    )
    condition = models.ForeignKey(
        Condition,
        verbose_name=_("condition"),
        on_delete=models.CASCADE,
        null=True,
        blank=True,
        related_name="+",
    )
    item = models.ForeignKey(
        Item,
        verbose_name=_("item"),
        on_delete=models.CASCADE,
        null=True,
        blank=True,
        related_name="+",
    )
    incoming = models.CharField(
        _("incoming"), max_length=100, help_text=_("The file's name under incoming/.")
    )
    original_name = models.CharField(_("original name"), max_length=255)
    status = models.CharField(
        _("status"), max_length=10, choices=Status.choices, default=Status.QUEUED, db_index=True
    )
    done = models.PositiveIntegerField(_("done"), default=0, help_text=_("Clips converted so far."))
    total = models.PositiveIntegerField(
        _("total"), default=1, help_text=_("Clips the upload holds.")
    )
    message = models.TextField(
        _("message"), blank=True, help_text=_("What was saved, or why nothing was.")
    )
    created_at = models.DateTimeField(_("created at"), auto_now_add=True)

    class Meta:
        verbose_name = _("clip upload")
        verbose_name_plural = _("clip uploads")
        ordering = ["-created_at", "-pk"]

    def __str__(self) -> str:
        return f"{self.original_name} ({self.get_status_display().lower()})"

    @property
    def is_zip(self) -> bool:
        return self.condition_id is None
