"""Keep personal files (signed answers, signers' recordings) outside the public media.

Stimuli and ASL prompts are public and live under ``MEDIA_ROOT``. A participant's
webcam answer or a signer's recording is personal data: it lives under
``SIGNSTUDY_PRIVATE_MEDIA_ROOT``, which no URL maps to directly, and its URL is the
authenticated view :func:`studyplatform.views.private_media`.
"""

import os

from django.conf import settings
from django.core.files.storage import FileSystemStorage
from django.urls import reverse
from django.utils.deconstruct import deconstructible


@deconstructible
class PrivateStorage(FileSystemStorage):
    """Store files under ``SIGNSTUDY_PRIVATE_MEDIA_ROOT``, served only to those allowed."""

    @property
    def base_location(self):
        # Read at each use, not cached: tests and deployments move the root.
        return self._value_or_setting(self._location, settings.SIGNSTUDY_PRIVATE_MEDIA_ROOT)

    @property
    def location(self):
        return os.path.abspath(self.base_location)

    def url(self, name):
        """Return the authenticated view's URL of *name*."""
        return reverse("private_media", args=[name])


def private_storage() -> PrivateStorage:
    """Return the storage of personal files (a callable, so migrations name it)."""
    return PRIVATE_STORAGE


PRIVATE_STORAGE = PrivateStorage()
