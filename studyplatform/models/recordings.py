"""Record a signer's performance of an item: the Motion capture its conditions retime."""

from django.db import models
from django.utils.translation import gettext_lazy as _

from studyplatform.files.storage import private_storage
from studyplatform.models.items import Item

VIDEO_SUFFIXES = (".mp4", ".webm", ".mov", ".m4v")


class Recording(models.Model):
    """A recording of one item (video, ``.pose`` or BVH) and the motion made from it.

    An item's newest ready recording is its performance: every condition whose
    performance is a simulated capture or a recording retimes it (seed 000 §4.3). An
    older recording stays in use until a newer one is ready, so a failed capture loses
    nothing.
    """

    class Status(models.TextChoices):
        CAPTURING = "capturing", _("Capturing")
        READY = "ready", _("Ready")
        FAILED = "failed", _("Failed")

    item = models.ForeignKey(
        Item, verbose_name=_("item"), on_delete=models.CASCADE, related_name="recordings"
    )
    upload = models.FileField(
        _("upload"),
        upload_to="recordings/",
        storage=private_storage,
        help_text=_(
            "The file as uploaded: a video of the signer (MP4, WebM, MOV), a .pose "
            "file of landmarks, or a BVH motion."
        ),
    )
    motion = models.FileField(
        _("motion"),
        upload_to="recordings/",
        storage=private_storage,
        blank=True,
        help_text=_(
            "What clips are made from: the uploaded .pose or BVH file, or for a video "
            "the hand landmarks captured from it (.pose)."
        ),
    )
    sheet = models.FileField(
        _("sheet"),
        upload_to="recordings/",
        storage=private_storage,
        blank=True,
        help_text=_("For a video: a contact sheet of video frames above the hand fitted to them."),
    )
    mirrored = models.BooleanField(
        _("mirrored"),
        default=False,
        help_text=_("The video is mirrored (a front camera's selfie view)."),
    )
    one_hand = models.BooleanField(
        _("one hand"),
        default=False,
        help_text=_(
            "The video is a close-up of the signing hand only (captured as that hand "
            "whatever side it looks like)."
        ),
    )
    status = models.CharField(
        _("status"), max_length=10, choices=Status.choices, default=Status.CAPTURING, db_index=True
    )
    progress_percent = models.PositiveSmallIntegerField(_("progress percent"), default=0)
    quality = models.JSONField(
        _("quality"),
        default=dict,
        blank=True,
        help_text=_("Frames with the hand found, mean confidence, fit residual (mm), jitter."),
    )
    error = models.TextField(_("error"), blank=True)
    sha256 = models.CharField(_("SHA-256 of the upload"), max_length=64, blank=True)
    created_at = models.DateTimeField(_("created at"), auto_now_add=True)

    class Meta:
        verbose_name = _("recording")
        verbose_name_plural = _("recordings")
        ordering = ["item", "-created_at", "-pk"]

    def __str__(self) -> str:
        return f"{self.item.key}: {self.upload.name.rsplit('/', 1)[-1]}"

    @property
    def is_video(self) -> bool:
        """Return whether the upload is a video (captured before use)."""
        return self.upload.name.lower().endswith(VIDEO_SUFFIXES)
