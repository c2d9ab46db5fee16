"""Pack a study definition with the media files it names, and read such a bundle back.

A bundle is a zip holding ``study.json`` (the definition of :mod:`studyplatform.exchange`)
and, under ``files/``, each ASL video, poster and recording file the definition names by
its media name (``files/asl/consent.webm``). Importing it brings the files along, so an
import never has to name files already on the server, which may be someone else's.
"""

import io
import json
import zipfile
from typing import Any

from django.core.files.storage import default_storage

from studyplatform.lib import strict_json
from studyplatform.models import Recording, Study

DEFINITION = "study.json"
FILES = "files/"
MAX_MEMBERS = 10_000
MAX_UNPACKED_BYTES = 2 * 1024**3  # larger than any study's prompts and recordings


class BundleRejected(ValueError):
    """A bundle that cannot be read; the message says why."""


def storage_of(folder: str):
    """Return the storage that keeps files of media *folder* ("asl" or "recordings")."""
    if folder == "recordings":
        return Recording._meta.get_field("upload").storage  # private
    return default_storage


def definition_files(definition: dict[str, Any]) -> set[str]:
    """Return the media names a study definition refers to."""
    names = set()
    for row in definition.get("asl_videos") or []:
        if isinstance(row, dict):
            names.update(row.get(key) for key in ("video", "poster"))
    for row in definition.get("recordings") or []:
        if isinstance(row, dict):
            names.update(row.get(key) for key in ("upload", "motion", "sheet"))
    return {name for name in names if isinstance(name, str) and name}


def owned_files(owner) -> set[str]:
    """Return the media names the studies of *owner* refer to (theirs to reuse)."""
    from studyplatform.exchange import RECORDING_FILES, study_asl_videos

    names: set[str] = set()
    for study in Study.objects.filter(owner=owner):
        for video in study_asl_videos(study):
            names.update((video.video.name, video.poster.name))
    for row in Recording.objects.filter(item__study__owner=owner).values_list(*RECORDING_FILES):
        names.update(row)
    return {name for name in names if name}


def write_bundle(definition: dict[str, Any], out) -> None:
    """Write *definition* and the files it names (those that exist) as a zip to *out*."""
    text = definition_json(definition)
    with zipfile.ZipFile(out, "w", zipfile.ZIP_DEFLATED) as archive:
        archive.writestr(DEFINITION, text)
        for name in sorted(definition_files(definition)):
            storage = storage_of(name.partition("/")[0])
            if not storage.exists(name):
                continue
            # Videos are compressed already: stored as they are.
            info = zipfile.ZipInfo(FILES + name)
            info.compress_type = zipfile.ZIP_STORED
            with storage.open(name, "rb") as handle, archive.open(info, "w") as member:
                for block in iter(lambda: handle.read(1 << 20), b""):
                    member.write(block)


def definition_json(definition: dict[str, Any]) -> str:
    """Return *definition* as the indented JSON an export writes."""
    return json.dumps(definition, indent=2, ensure_ascii=False) + "\n"


def read_bundle(data: bytes) -> tuple[Any, dict[str, bytes]]:
    """Return the definition and the files (by media name) of the zip bundle *data*."""
    try:
        archive = zipfile.ZipFile(io.BytesIO(data))
    except zipfile.BadZipFile:
        raise BundleRejected("not a zip file") from None
    with archive:
        members = archive.infolist()
        if len(members) > MAX_MEMBERS:
            raise BundleRejected(f"a zip of more than {MAX_MEMBERS} files")
        if sum(member.file_size for member in members) > MAX_UNPACKED_BYTES:
            raise BundleRejected(f"larger than {MAX_UNPACKED_BYTES // 1024**3} GB unpacked")
        if DEFINITION not in archive.namelist():
            raise BundleRejected(f"a zip without {DEFINITION}")
        try:
            definition = strict_json.loads(archive.read(DEFINITION))
        except strict_json.JsonRejected as error:
            raise BundleRejected(f"a zip whose {DEFINITION} is {error}") from None
        files = {
            member.filename[len(FILES):]: archive.read(member)
            for member in members
            if member.filename.startswith(FILES) and not member.is_dir()
        }  # fmt: skip
    return definition, files
