"""Pack a study definition with the media files it names, and read such a bundle back.

A bundle is a zip holding ``study.json`` (the definition of :mod:`studyplatform.lib.exchange`)
and, under ``files/``, each ASL video, poster and recording file the definition names by
its media name (``files/asl/consent.webm``). Importing it brings the files along, so an
import never has to name files already on the server, which may be someone else's.
"""

import hashlib
import io
import json
import tempfile
import zipfile
import zlib
from typing import IO, Any

from django.core.files.storage import default_storage

from studyplatform.lib import strict_json
from studyplatform.models import Recording, Study, UploadedClip

DEFINITION = "study.json"
FILES = "files/"
MAX_MEMBERS = 10_000
MAX_DEFINITION_BYTES = 5 * 1024**2  # as for a definition uploaded on its own
MAX_MEMBER_BYTES = 300 * 1024**2  # the largest ASL video or recording an upload may be
MAX_UNPACKED_BYTES = 1024**3  # larger than any study's prompts and recordings
BLOCK_BYTES = 1 << 20
# A member flagged encrypted (PKWARE APPNOTE 4.4.4, bit 0): zipfile asks for a password.
ENCRYPTED = 0x1
# What reading a damaged zip raises: bad headers, damaged deflate data (zlib.error), a
# compression zipfile lacks (NotImplementedError), an encrypted member (RuntimeError).
UNREADABLE_ZIP = (
    zipfile.BadZipFile,
    zipfile.LargeZipFile,
    zlib.error,
    EOFError,
    NotImplementedError,
    RuntimeError,
    OSError,
)
SPOOL_BYTES = 8 << 20  # a member larger than this is unpacked to disk, not memory


class BundleRejected(ValueError):
    """A bundle that cannot be read; the message says why."""


def storage_of(folder: str):
    """Return the storage that keeps files of media *folder* ("asl", "recordings" or
    "uploads")."""
    if folder in ("recordings", "uploads"):
        return Recording._meta.get_field("upload").storage  # private
    return default_storage


def _list(value: Any) -> list:
    return value if isinstance(value, list) else []


def definition_files(definition: dict[str, Any]) -> set[str]:
    """Return the media names a study definition refers to."""
    names = set()
    for row in _list(definition.get("asl_videos")):
        if isinstance(row, dict):
            names.update(row.get(key) for key in ("video", "poster"))
    for row in _list(definition.get("recordings")):
        if isinstance(row, dict):
            names.update(row.get(key) for key in ("upload", "motion", "sheet"))
    for row in _list(definition.get("uploaded_clips")):
        if isinstance(row, dict):
            names.update(row.get(key) for key in ("video", "poster"))
    return {name for name in names if isinstance(name, str) and name}


def owned_files(owner) -> set[str]:
    """Return the media names the studies of *owner* refer to (theirs to reuse)."""
    from studyplatform.lib.exchange import RECORDING_FILES, UPLOAD_FILES, study_asl_videos

    names: set[str] = set()
    for study in Study.objects.filter(owner=owner):
        for video in study_asl_videos(study):
            names.update((video.video.name, video.poster.name))
    for row in Recording.objects.filter(item__study__owner=owner).values_list(*RECORDING_FILES):
        names.update(row)
    uploads = UploadedClip.objects.filter(condition__study__owner=owner)
    for row in uploads.values_list(*UPLOAD_FILES):
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


class BundleFiles:
    """The media files of a bundle, each unpacked when the import asks for it.

    Nothing is trusted from the zip's directory: every member is decompressed through a
    counter that stops at MAX_MEMBER_BYTES for one file and MAX_UNPACKED_BYTES for all,
    into a spooled temporary file, so a zip bomb costs a bounded amount of disk and a
    flat amount of memory (issue 33: a 1 MB bundle with a 1 GiB member was read whole).
    """

    def __init__(self, archive: zipfile.ZipFile | None = None):
        self._archive, self._unpacked = archive, 0
        self._names = (
            {
                m.filename[len(FILES) :]
                for m in archive.infolist()
                if m.filename.startswith(FILES) and not m.is_dir()
            }
            if archive is not None
            else set()
        )

    def __contains__(self, name: object) -> bool:
        return name in self._names

    def __len__(self) -> int:
        return len(self._names)

    def unpack(self, name: str) -> tuple[str, IO[bytes]]:
        """Return the SHA-256 and an open temporary copy (at its start) of file *name*."""
        copy = tempfile.SpooledTemporaryFile(SPOOL_BYTES)  # noqa: SIM115 (the caller closes it)
        try:
            digest = self._copy(name, copy)
        except UNREADABLE_ZIP as error:
            copy.close()
            raise BundleRejected(f"a zip whose {name} cannot be unpacked ({error})") from None
        except BaseException:
            copy.close()
            raise
        copy.seek(0)
        return digest, copy

    def _copy(self, name: str, copy: IO[bytes]) -> str:
        """Decompress member *name* into *copy* within the caps; return its SHA-256."""
        digest, size = hashlib.sha256(), 0
        member_mb, total_gb = MAX_MEMBER_BYTES // 1024**2, MAX_UNPACKED_BYTES // 1024**3
        with self._archive.open(FILES + name) as member:
            for block in iter(lambda: member.read(BLOCK_BYTES), b""):
                size += len(block)
                self._unpacked += len(block)
                if size > MAX_MEMBER_BYTES:
                    raise BundleRejected(f"{name} is larger than {member_mb} MB unpacked")
                if self._unpacked > MAX_UNPACKED_BYTES:
                    raise BundleRejected(f"larger than {total_gb} GB unpacked")
                digest.update(block)
                copy.write(block)
        return digest.hexdigest()


def read_bundle(source) -> tuple[Any, BundleFiles]:
    """Return the definition and the files (by media name) of the zip bundle *source*.

    *source* is the zip as bytes, a path or an open binary file (kept open while the
    files are used). Refused: more than MAX_MEMBERS members, a definition over
    MAX_DEFINITION_BYTES, and any member the definition does not name.
    """
    if isinstance(source, bytes | bytearray):
        source = io.BytesIO(source)
    try:
        archive = zipfile.ZipFile(source)
    except (zipfile.BadZipFile, OSError, EOFError):
        raise BundleRejected("not a zip file") from None
    members = archive.infolist()
    if len(members) > MAX_MEMBERS:
        raise BundleRejected(f"a zip of more than {MAX_MEMBERS} files")
    if DEFINITION not in archive.namelist():
        raise BundleRejected(f"a zip without {DEFINITION}")
    try:
        with archive.open(DEFINITION) as member:
            text = member.read(MAX_DEFINITION_BYTES + 1)
    except UNREADABLE_ZIP as error:
        raise BundleRejected(f"a zip whose {DEFINITION} cannot be unpacked ({error})") from None
    if len(text) > MAX_DEFINITION_BYTES:
        raise BundleRejected(
            f"a zip whose {DEFINITION} is larger than {MAX_DEFINITION_BYTES // 1024**2} MB"
        )
    try:
        definition = strict_json.loads(text)
    except strict_json.JsonRejected as error:
        raise BundleRejected(f"a zip whose {DEFINITION} is {error}") from None
    named = (
        {FILES + name for name in definition_files(definition)}
        if isinstance(definition, dict)
        else set()
    )
    for member in members:
        if member.filename != DEFINITION and not member.is_dir() and member.filename not in named:
            raise BundleRejected(
                f"a zip with a file its {DEFINITION} does not name: {member.filename[:200]!r}"
            )
    return definition, BundleFiles(archive)
