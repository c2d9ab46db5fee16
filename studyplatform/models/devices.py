"""Remember the browsers that signed in: the server's half of a known-device cookie."""

from django.conf import settings
from django.db import models


class KnownDevice(models.Model):
    """A browser that signed in as *user*: its cookie's token, kept here as a SHA-256.

    A cookie counts as a known device only while its row is here, so a leaked secret key
    forges no device (issue 51: forged cookies let 14 wrong passwords through uncounted).
    """

    user = models.ForeignKey(
        settings.AUTH_USER_MODEL, on_delete=models.CASCADE, related_name="known_devices"
    )
    token_sha256 = models.CharField(max_length=64, unique=True)
    created_at = models.DateTimeField(auto_now_add=True, db_index=True)

    class Meta:
        ordering = ["-created_at"]

    def __str__(self) -> str:
        return f"a browser of {self.user} since {self.created_at:%Y-%m-%d}"
