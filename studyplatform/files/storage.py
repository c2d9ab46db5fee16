"""Keep personal files (signed answers, signers' recordings) outside the public media.

Stimuli and ASL prompts are public and live under ``MEDIA_ROOT``. A participant's
webcam answer or a signer's recording is personal data: it lives under
``SIGNSTUDY_PRIVATE_MEDIA_ROOT``, which no URL maps to directly, and its URL is the
authenticated view :func:`studyplatform.views.private_media`.
"""

import os

from django.conf import settings
from django.core.files import File
from django.core.files.storage import FileSystemStorage
from django.urls import reverse
from django.utils.deconstruct import deconstructible

from studyplatform.files.media_types import MediaRejected, safe_name, sniff_file


class ContentNamedMixin:
    """Name every saved file by what its content is, and refuse any other kind.

    The last line of defence of issue 33's rule (no upload is ever served as a page or
    a script): whatever path stored it, a file's extension, and so the type it is served
    with, comes from its first bytes (studyplatform.files.media_types).
    """

    def save(self, name, content, max_length=None):
        if name is None:
            name = content.name
        if not hasattr(content, "chunks"):
            content = File(content, name)
        kind = sniff_file(content)
        if kind is None:
            raise MediaRejected(f"“{os.path.basename(name)}” is no video, picture or motion file.")
        return super().save(safe_name(name, kind), content, max_length)


@deconstructible
class MediaStorage(ContentNamedMixin, FileSystemStorage):
    """Store public media (clips, posters, ASL prompts) under names their content gives."""


@deconstructible
class PrivateStorage(ContentNamedMixin, FileSystemStorage):
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
