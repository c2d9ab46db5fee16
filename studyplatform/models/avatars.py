"""Keep researchers' own avatars: humanoid glTF 2.0 / VRM files that film conditions."""

from django.conf import settings
from django.db import models
from django.utils.translation import gettext_lazy as _

from studyplatform.files.storage import private_storage


class Avatar(models.Model):
    """A humanoid avatar a researcher uploaded (GLB or VRM), with what the engine makes
    of it: its bones mapped to the engine's, the face channels it plays, preview stills.

    A condition filmed with it renders the engine's motion retargeted onto it; the
    file's SHA-256 is part of each clip's hash, so a new mapping (saved in the file)
    renders new clips.
    """

    class Status(models.TextChoices):
        PREPARING = "preparing", _("Rendering previews")
        READY = "ready", _("Ready")
        FAILED = "failed", _("Failed")

    owner = models.ForeignKey(
        settings.AUTH_USER_MODEL,
        verbose_name=_("owner"),
        on_delete=models.PROTECT,
        related_name="avatars",
    )
    name = models.CharField(_("name"), max_length=100)
    file = models.FileField(
        _("file"),
        upload_to="avatars/",
        storage=private_storage,
        help_text=_("The avatar as stored: the upload with the bone mapping saved in it."),
    )
    sha256 = models.CharField(_("SHA-256 of the file"), max_length=64, db_index=True)
    original_name = models.CharField(_("original name"), max_length=255, blank=True)
    licence = models.CharField(
        _("licence"),
        max_length=200,
        help_text=_(
            "Under what terms you may show it, e.g. 'CC0', 'CC BY 4.0', 'VRoid "
            "Hub: avatar use allowed'. Reports of studies that use it name it."
        ),
    )
    source = models.CharField(
        _("source"),
        max_length=300,
        blank=True,
        help_text=_("Where it comes from: a URL, its author."),
    )
    bone_mapping = models.JSONField(
        _("bone mapping"),
        default=dict,
        blank=True,
        help_text=_(
            "Your own mapping, avatar joint → engine joint, for joints the engine "
            "does not recognise (an empty engine joint unmaps one). Saved in the file."
        ),
    )
    report = models.JSONField(
        _("report"),
        default=dict,
        blank=True,
        help_text=_(
            "What the engine found: joints mapped and not, finger bones missing, "
            "face channels it plays, height."
        ),
    )
    still_rest = models.FileField(
        _("still rest"), upload_to="avatars/", storage=private_storage, blank=True
    )
    still_letter = models.FileField(
        _("still letter"), upload_to="avatars/", storage=private_storage, blank=True
    )
    still_face = models.FileField(
        _("still face"), upload_to="avatars/", storage=private_storage, blank=True
    )
    status = models.CharField(
        _("status"), max_length=10, choices=Status.choices, default=Status.PREPARING, db_index=True
    )
    error = models.TextField(_("error"), blank=True)
    created_at = models.DateTimeField(_("created at"), auto_now_add=True)

    class Meta:
        verbose_name = _("avatar")
        verbose_name_plural = _("avatars")
        ordering = ["owner", "name", "pk"]

    def __str__(self) -> str:
        return self.name

    @property
    def signs(self) -> bool:
        """Return whether its mapping reaches every arm joint signing turns (both
        shoulders, elbows and wrists); a report made before that was checked says yes."""
        return not self.report.get("missing_body")

    @property
    def fingerspells(self) -> bool:
        """Return whether its right hand has every bone fingerspelling moves."""
        return not (self.report.get("missing_fingers") or {}).get("right")
