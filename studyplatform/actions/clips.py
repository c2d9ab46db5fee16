"""Take researchers' own videos as the clips of a condition: one file, or a zip of many.

A condition whose source is *uploaded* shows one video per item that the researcher
brings (a filmed signer, another lab's animation). Each file is checked and made
playable (:mod:`studyplatform.files.video_files`), stored in private media under its
SHA-256, and becomes the item's ready clip in that condition at once. A zip is taken
whole or not at all: its manifest (``item,condition,file``) and every file it names are
checked before anything is stored. A clip participants may have seen is never replaced:
that takes a new version of the study.
"""

import csv
import io
import tempfile
import zipfile
from dataclasses import dataclass
from pathlib import Path, PurePosixPath

from django.core.exceptions import ValidationError
from django.core.files import File
from django.db import transaction

from studyplatform.actions.media import delete_unused_files_on_commit
from studyplatform.actions.stimuli import record_missing_stimulus, record_uploaded_stimulus
from studyplatform.files.media_types import MediaRejected, sniff_file
from studyplatform.files.storage import PRIVATE_STORAGE
from studyplatform.files.video_files import MAX_CLIP_BYTES, PreparedClip, copy_upload, prepare_clip
from studyplatform.lib.bundle import ENCRYPTED, UNREADABLE_ZIP
from studyplatform.models import Condition, Item, Study, UploadedClip
from studyplatform.models.studies import check_unlocked

MANIFEST_COLUMNS = ("item", "condition", "file")
MAX_MANIFEST_BYTES = 1024**2
MAX_ZIP_MEMBERS = 2000
MAX_ZIP_UNPACKED_BYTES = 8 * 1024**3
# Video barely compresses (a rendered clip deflates to ~97 % of its size); a member
# that claims to unpack to many times its packed size is a zip bomb, not a clip.
MAX_PACKING_RATIO = 20
SMALL_MEMBER_BYTES = 1024**2  # a small file may pack well: its ratio is not checked


class ClipUploadRejected(ValidationError):
    """An upload that cannot become a clip; nothing was stored."""


@dataclass(frozen=True)
class ClipRow:
    """One clip a manifest names, found in the study and in the zip."""

    condition: Condition
    item: Item
    member: zipfile.ZipInfo


def _check_target(condition: Condition, item: Item) -> None:
    if not condition.is_uploaded:
        raise ClipUploadRejected(
            f"Condition {condition.key!r} renders its clips; set its clips to “uploaded” "
            "to bring your own."
        )
    if item.study_id != condition.study_id:
        raise ClipUploadRejected(f"Item {item.key!r} belongs to another study.")


def _store(condition: Condition, item: Item, prepared: PreparedClip, name: str) -> UploadedClip:
    """Save *prepared* as the clip of *item* in *condition* (inside a transaction)."""
    clip = UploadedClip.objects.filter(condition=condition, item=item).first()
    old = (clip.video.name, clip.poster.name) if clip is not None else ()
    clip = clip or UploadedClip(condition=condition, item=item)
    for field, path, suffix in (
        ("video", prepared.video, prepared.suffix),
        ("poster", prepared.poster, ".png"),
    ):
        stored = f"uploads/{prepared.sha256}{suffix}"
        if not PRIVATE_STORAGE.exists(stored):
            with open(path, "rb") as handle:
                stored = PRIVATE_STORAGE.save(stored, File(handle))
        getattr(clip, field).name = stored
    clip.original_name = PurePosixPath(name).name[:255]
    for fact in (
        "sha256",
        "source_sha256",
        "source_codec",
        "converted",
        "duration_ms",
        "frame_count",
        "frame_rate",
        "width",
        "height",
        "size_bytes",
    ):
        setattr(clip, fact, getattr(prepared, fact))
    clip.save()
    record_uploaded_stimulus(clip)
    delete_unused_files_on_commit(PRIVATE_STORAGE, old)
    return clip


def check_clip(condition: Condition, item: Item, upload) -> None:
    """Raise ClipUploadRejected for a condition that renders its clips, an item of
    another study, a study whose clips participants may have seen, a file over 500 MB
    or one that is not a video by its content (what needs no decoding)."""
    _check_target(condition, item)
    check_unlocked(condition.study)
    name = getattr(upload, "name", "") or "clip"
    if (getattr(upload, "size", 0) or 0) > MAX_CLIP_BYTES:
        raise ClipUploadRejected(f"“{name}” is larger than {MAX_CLIP_BYTES // 1024**2} MB.")
    kind = sniff_file(upload)
    if kind is None or kind.family != "video":
        raise ClipUploadRejected(
            f"“{name}” is not a video (MP4, WebM or MOV), judged by its content."
        )


def do_upload_clip(condition: Condition, item: Item, upload) -> UploadedClip:
    """Store *upload* (a video file) as the clip of *item* in *condition*; return it.

    Raise ClipUploadRejected for what :func:`check_clip` refuses, or a file that is
    not a whole video of at most 500 MB, 10 minutes and 4096 pixels a side.
    """
    check_clip(condition, item, upload)
    name = getattr(upload, "name", "") or "clip"
    with tempfile.TemporaryDirectory() as folder:
        source = copy_upload(upload, Path(folder) / "upload")
        try:
            prepared = prepare_clip(source, Path(folder), f"“{name}”")
        except MediaRejected as error:
            raise ClipUploadRejected(error.messages[0]) from None
        with transaction.atomic(durable=True):
            return _store(condition, item, prepared, name)


def _manifest_member(archive: zipfile.ZipFile) -> zipfile.ZipInfo:
    """Return the zip's manifest: ``manifest.csv``, else its only CSV file."""
    csvs = [m for m in archive.infolist() if m.filename.lower().endswith(".csv")]
    named = [m for m in csvs if PurePosixPath(m.filename).name.lower() == "manifest.csv"]
    if len(named) == 1 or len(csvs) == 1:
        return (named or csvs)[0]
    if not csvs:
        raise ClipUploadRejected("The zip has no manifest.csv (columns item,condition,file).")
    raise ClipUploadRejected("The zip has several CSV files and no manifest.csv among them.")


def _manifest_rows(archive: zipfile.ZipFile, member: zipfile.ZipInfo) -> list[dict[str, str]]:
    if member.file_size > MAX_MANIFEST_BYTES:
        raise ClipUploadRejected(f"{member.filename} is larger than 1 MB.")
    try:
        text = archive.read(member).decode("utf-8-sig")
    except UnicodeDecodeError:
        raise ClipUploadRejected(f"{member.filename} is not UTF-8 text.") from None
    try:
        return _parsed_manifest(member.filename, text)
    except csv.Error as error:  # a field over the csv module's limit, a NUL, …
        raise ClipUploadRejected(f"{member.filename} is not a readable CSV ({error}).") from None


def _parsed_manifest(filename: str, text: str) -> list[dict[str, str]]:
    reader = csv.DictReader(io.StringIO(text))
    columns = [c.strip().lower() for c in reader.fieldnames or []]
    missing = [c for c in MANIFEST_COLUMNS if c not in columns]
    if missing:
        raise ClipUploadRejected(
            f"{filename} has no {', '.join(missing)} column; it needs "
            f"{','.join(MANIFEST_COLUMNS)} (one row per clip)."
        )
    reader.fieldnames = columns
    rows = [{k: (v or "").strip() for k, v in row.items() if k} for row in reader]
    if not rows:
        raise ClipUploadRejected(f"{filename} names no clip.")
    return rows


def _check_member(member: zipfile.ZipInfo, where: str) -> None:
    """Refuse a member that is encrypted, too large or unpacks to far more than it packs."""
    if member.flag_bits & ENCRYPTED:
        raise ClipUploadRejected(
            f"{where}: {member.filename} is encrypted; zip it without a password."
        )
    if member.file_size > MAX_CLIP_BYTES:
        raise ClipUploadRejected(
            f"{where}: {member.filename} unpacks to more than {MAX_CLIP_BYTES // 1024**2} MB."
        )
    ratio = member.file_size / max(member.compress_size, 1)
    if member.file_size > SMALL_MEMBER_BYTES and ratio > MAX_PACKING_RATIO:
        raise ClipUploadRejected(
            f"{where}: {member.filename} unpacks to {ratio:.0f} times its packed size, "
            "which no video does (a zip bomb?)."
        )


def _clip_rows(study: Study, archive: zipfile.ZipFile) -> list[ClipRow]:
    """Return the clips the zip's manifest names, each checked against study and zip."""
    members = archive.infolist()
    if len(members) > MAX_ZIP_MEMBERS:
        raise ClipUploadRejected(f"The zip holds over {MAX_ZIP_MEMBERS} files.")
    manifest = _manifest_member(archive)
    by_name = {m.filename: m for m in members if not m.is_dir()}
    base = PurePosixPath(manifest.filename).parent
    items = {item.key: item for item in study.items.all()}
    conditions = {condition.key: condition for condition in study.conditions.all()}
    rows, seen, unpacked = [], set(), 0
    for number, row in enumerate(_manifest_rows(archive, manifest), start=2):
        where = f"{manifest.filename}, line {number}"
        item, condition = items.get(row["item"]), conditions.get(row["condition"])
        if item is None:
            raise ClipUploadRejected(f"{where}: the study has no item {row['item']!r}.")
        if condition is None:
            raise ClipUploadRejected(f"{where}: the study has no condition {row['condition']!r}.")
        try:
            _check_target(condition, item)
        except ClipUploadRejected as error:
            raise ClipUploadRejected(f"{where}: {error.messages[0]}") from None
        if (condition.pk, item.pk) in seen:
            raise ClipUploadRejected(f"{where}: a second clip of {item.key} in {condition.key}.")
        seen.add((condition.pk, item.pk))
        member = by_name.get(str(base / row["file"])) or by_name.get(row["file"])
        if not row["file"] or member is None:
            raise ClipUploadRejected(f"{where}: the zip has no file {row['file']!r}.")
        _check_member(member, where)
        unpacked += member.file_size
        if unpacked > MAX_ZIP_UNPACKED_BYTES:
            raise ClipUploadRejected(
                f"The clips unpack to more than {MAX_ZIP_UNPACKED_BYTES // 1024**3} GB."
            )
        rows.append(ClipRow(condition, item, member))
    return rows


def _unpack(archive: zipfile.ZipFile, member: zipfile.ZipInfo, target: Path) -> Path:
    """Write *member* to *target*, reading no more than it claims to hold."""
    with archive.open(member) as packed, open(target, "wb") as out:
        left = member.file_size
        while block := packed.read(min(1 << 20, left + 1)):
            left -= len(block)
            if left < 0:
                raise ClipUploadRejected(f"{member.filename} holds more than its zip entry says.")
            out.write(block)
    return target


def check_clips_zip(study: Study, upload) -> int:
    """Return how many clips a zip's manifest names, each checked against the study and
    the zip (what needs no decoding); ClipUploadRejected names the first problem."""
    check_unlocked(study)
    try:
        archive = zipfile.ZipFile(upload)
    except (zipfile.BadZipFile, OSError):
        raise ClipUploadRejected("The file is not a zip archive.") from None
    with archive:
        try:
            return len(_clip_rows(study, archive))
        except UNREADABLE_ZIP as error:
            raise ClipUploadRejected(f"The zip cannot be read: {error}.") from None


def do_import_clips(study: Study, upload, progress=None) -> list[UploadedClip]:
    """Store every clip a zip's manifest names (``item,condition,file``); return them.

    All or nothing: a manifest naming an unknown item or condition, a rendered
    condition or a missing file, a file that is not a whole video, an oversized member
    or a zip bomb raise ClipUploadRejected, and no clip is stored. *progress* is told
    how many clips are converted as each one is.
    """
    check_unlocked(study)
    try:
        archive = zipfile.ZipFile(upload)
    except (zipfile.BadZipFile, OSError):
        raise ClipUploadRejected("The file is not a zip archive.") from None
    with archive, tempfile.TemporaryDirectory() as folder:
        try:
            rows = _clip_rows(study, archive)
            prepared = []
            for number, row in enumerate(rows):
                if progress is not None:
                    progress(number)
                place = Path(folder) / str(number)
                place.mkdir()
                source = _unpack(archive, row.member, place / "upload")
                try:
                    prepared.append(prepare_clip(source, place, row.member.filename))
                except MediaRejected as error:
                    raise ClipUploadRejected(error.messages[0]) from None
        except UNREADABLE_ZIP as error:
            raise ClipUploadRejected(f"The zip cannot be read: {error}.") from None
        with transaction.atomic(durable=True):
            return [
                _store(row.condition, row.item, ready, row.member.filename)
                for row, ready in zip(rows, prepared, strict=True)
            ]


def do_remove_uploaded_clip(clip: UploadedClip) -> None:
    """Delete an uploaded clip; its item shows no clip in that condition until another
    is uploaded. Refused once participants may have seen it."""
    check_unlocked(clip.condition.study)
    with transaction.atomic(durable=True):
        names = (clip.video.name, clip.poster.name)
        clip.delete()
        record_missing_stimulus(clip.condition, clip.item)
        delete_unused_files_on_commit(PRIVATE_STORAGE, names)
