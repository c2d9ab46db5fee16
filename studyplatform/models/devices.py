"""Remember the browsers that signed in: the server's half of a known-device cookie."""

from django.conf import settings
from django.db import models
from django.utils.translation import gettext
from django.utils.translation import gettext_lazy as _


class KnownDevice(models.Model):
    """A browser that signed in as *user*: its cookie's token, kept here as a SHA-256.

    A cookie counts as a known device only while its row is here, so a leaked secret key
    forges no device (issue 51: forged cookies let 14 wrong passwords through uncounted).
    """

    user = models.ForeignKey(
        settings.AUTH_USER_MODEL,
        verbose_name=_("user"),
        on_delete=models.CASCADE,
        related_name="known_devices",
    )
    token_sha256 = models.CharField(_("token sha256"), max_length=64, unique=True)
    created_at = models.DateTimeField(_("created at"), auto_now_add=True, db_index=True)

    class Meta:
        verbose_name = _("known device")
        verbose_name_plural = _("known devices")
        ordering = ["-created_at"]

    def __str__(self) -> str:
        return gettext("a browser of %(user)s since %(date)s") % {
            "user": self.user,
            "date": f"{self.created_at:%Y-%m-%d}",
        }
