"""Bring the media files a study definition names into an import: checked, stored, shared."""

from pathlib import PurePosixPath
from typing import Any

from django.core.exceptions import ValidationError
from django.core.files import File

from studyplatform.actions.recordings import check_motion_file
from studyplatform.files.media_types import MediaRejected, check_upload
from studyplatform.lib.bundle import BundleFiles, BundleRejected, owned_files, storage_of


class StudyImportError(ValueError):
    """A study definition that cannot be imported; the message names the problem."""


# What each media name of a definition must be, by content.
ASL_VIDEO, ASL_POSTER = ("video",), ("image",)
RECORDING_KINDS = {
    "upload": ("video", "motion", "model"),
    "motion": ("motion",),
    "sheet": ("image",),
}
UPLOAD_KINDS = {"video": ("video",), "poster": ("image",)}


class ImportedMedia:
    """Resolve the media names of a definition being imported (see do_import_study)."""

    def __init__(self, owner, files: BundleFiles | None, allowed: set[str]):
        self.owner, self.allowed, self.stored = owner, set(allowed), []
        self.files = files if files is not None else BundleFiles()
        self._owned: set[str] | None = None  # the owner's files, read when first needed

    def resolve(
        self, name: Any, folder: str, families: tuple[str, ...], whose: str, where: str
    ) -> str | None:
        """Return the name to store for *name* ("" for none, None if it is not here).

        A bundled file is checked by content (one of *families*, whole) and stored under
        its hash and the extension of what it is. A name already in media is only
        looked up when it is the owner's: "not yours" and "not there" read the same, so
        an import never tells whether another researcher has a file of that name.
        """
        _check_media_file(name, folder, whose, where)
        if not name:
            return ""
        storage = storage_of(folder)
        if name in self.files:
            try:
                digest, content = self.files.unpack(name)
            except BundleRejected as error:
                raise StudyImportError(f"{where}: the bundle is {error}.") from None
            with content:
                try:
                    kind = check_upload(content, families, f"{name!r}")
                except MediaRejected as error:
                    raise StudyImportError(f"{where}: {error.messages[0]}") from None
                if kind.family in ("motion", "model"):  # BVH, .pose, FBX; glTF (issue 51)
                    try:
                        check_motion_file(name, content.read(), kind)
                    except ValidationError as error:
                        raise StudyImportError(f"{where}: {error.messages[0]}") from None
                    content.seek(0)
                stored = f"{folder}/{digest[:32]}{kind.suffix}"
                if not storage.exists(stored):
                    stored = storage.save(stored, File(content, name=stored))
                    self.stored.append((storage, stored))
            return stored
        if not (name in self.allowed or self.owner.is_superuser):
            if self._owned is None:
                self._owned = owned_files(self.owner)
            if name not in self._owned:
                return None
        return name if storage.exists(name) else None


def _check_media_file(name: Any, folder: str, whose: str, where: str) -> None:
    """Refuse a file name (empty: none) that is not one storage gives a file of *folder*
    (``folder/<name>``: no way out of media, nothing a definition could point elsewhere)."""
    if not name:
        return
    parts = PurePosixPath(name).parts if isinstance(name, str) else ()
    if not (len(parts) == 2 and parts[0] == folder and parts[1] not in ("", ".", "..")):
        raise StudyImportError(f"{where}: {name!r} is not {whose} file ({folder}/<name> in media).")
