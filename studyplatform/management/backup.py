"""Back up the whole installation into one archive, and restore it with a verification.

An archive (``.tar.gz``) holds ``manifest.json`` (format, time, row counts per model,
SHA-256 of every file), ``data.json`` (Django's ``dumpdata`` of every model, with
natural keys for content types and permissions, so it loads into SQLite or PostgreSQL
alike) and the files of the public media root (``media/``) and the private one
(``private/``), and ``withdrawals.jsonl``, the withdrawal ledger
(:mod:`studyplatform.files.ledger`).
A restore loads it into a migrated, empty database, puts the files back, and checks every
count and checksum against the manifest; any difference is an error. It then applies
every withdrawal that this installation's ledger or the archive's records: a participant
who withdrew after the backup was made stays withdrawn, data and files (issue 33).
"""

import hashlib
import io
import json
import shutil
import tarfile
import tempfile
from dataclasses import dataclass
from pathlib import Path

from django.apps import apps
from django.conf import settings
from django.core.management import call_command
from django.db import transaction
from django.utils import timezone

from stimuli.clips import file_sha256
from studyplatform.files import ledger
from synthesis.formats import check_header

FORMAT = "signstudy.backup"
VERSION = 1
# Rebuilt by `migrate` (content types, permissions) or worthless in another installation
# (sessions, sign-in attempts).
EXCLUDED = ("contenttypes", "auth.permission", "sessions", "axes")
LEDGER = "withdrawals.jsonl"


class BackupError(Exception):
    """An archive that cannot be made or restored; the message says what is wrong."""


@dataclass(frozen=True)
class BackupSummary:
    """What an archive holds, or what a restore put back and verified."""

    rows: int
    files: int
    bytes: int
    # A restore's re-applied withdrawals: the numbers of the participants withdrawn again.
    withdrawn_again: tuple[int, ...] = ()


def _roots() -> dict[str, Path]:
    return {
        "media": Path(settings.MEDIA_ROOT),
        "private": Path(settings.SIGNSTUDY_PRIVATE_MEDIA_ROOT),
    }


def _counts() -> dict[str, int]:
    """Return the row count of every model the archive holds."""
    counts = {}
    for model in apps.get_models():
        label = model._meta.label_lower
        if model._meta.app_label in EXCLUDED or label in EXCLUDED or model._meta.proxy:
            continue
        counts[label] = model._default_manager.count()
    return counts


def make_backup(out: Path) -> BackupSummary:
    """Write the database and every media file to the archive *out*."""
    files: dict[str, str] = {}
    size = 0
    with tempfile.TemporaryDirectory() as scratch:
        data = Path(scratch) / "data.json"
        with transaction.atomic():  # one consistent snapshot of the rows and their counts
            call_command(
                "dumpdata",
                exclude=list(EXCLUDED),
                natural_foreign=True,
                natural_primary=True,
                output=str(data),
                verbosity=0,
            )
            counts = _counts()
        out.parent.mkdir(parents=True, exist_ok=True)
        with tarfile.open(out, "w:gz") as archive:
            archive.add(data, "data.json")
            ledger_text = _ledger_bytes()
            _add_bytes(archive, LEDGER, ledger_text)
            for prefix, root in _roots().items():
                for path in sorted(p for p in root.rglob("*") if p.is_file()):
                    name = f"{prefix}/{path.relative_to(root).as_posix()}"
                    files[name] = file_sha256(path)
                    size += path.stat().st_size
                    archive.add(path, name)
            manifest = {
                "format": FORMAT,
                "version": VERSION,
                "created_at": timezone.now().isoformat(),
                "counts": counts,
                "files": files,
                "data_sha256": file_sha256(data),
                "ledger_sha256": hashlib.sha256(ledger_text).hexdigest(),
            }
            _add_bytes(
                archive, "manifest.json", json.dumps(manifest, indent=1, sort_keys=True).encode()
            )
    return BackupSummary(rows=sum(counts.values()), files=len(files), bytes=size)


def _add_bytes(archive: tarfile.TarFile, name: str, data: bytes) -> None:
    info = tarfile.TarInfo(name)
    info.size = len(data)
    archive.addfile(info, io.BytesIO(data))


def _ledger_bytes() -> bytes:
    """Return the withdrawal ledger's bytes as they are now (empty: no withdrawal yet)."""
    try:
        return ledger.ledger_path().read_bytes()
    except FileNotFoundError:
        return b""


def _archived_ledger(archive: tarfile.TarFile, manifest: dict) -> list[ledger.LedgerEntry]:
    """Return the archive's ledger (an archive from before ledgers has none)."""
    if "ledger_sha256" not in manifest:
        return []
    try:
        text = archive.extractfile(LEDGER).read()
    except (KeyError, AttributeError):
        raise BackupError(f"The archive has no {LEDGER} though its manifest names one.") from None
    if hashlib.sha256(text).hexdigest() != manifest["ledger_sha256"]:
        raise BackupError(f"{LEDGER} does not match its checksum: the archive is damaged.")
    try:
        return ledger.parse(text.decode("utf-8"), LEDGER)
    except (UnicodeDecodeError, ValueError) as error:
        raise BackupError(f"The archive's {LEDGER} cannot be read ({error}).") from None


def _read_manifest(archive: tarfile.TarFile) -> dict:
    try:
        manifest = json.load(archive.extractfile("manifest.json"))
    except (KeyError, ValueError) as error:
        raise BackupError(f"The archive has no readable manifest.json ({error}).") from None
    check_header(manifest, FORMAT, VERSION, "SignStudy backup", BackupError)
    return manifest


def _database_is_empty() -> bool:
    return not any(
        count
        for label, count in _counts().items()
        if label.startswith("studyplatform.") or label == "auth.user"
    )


def restore_backup(archive_path: Path, *, replace: bool = False) -> BackupSummary:
    """Restore the archive into this installation and verify it against its manifest.

    The database must be migrated and empty, unless *replace*, which deletes what it
    holds first (``flush``). The whole archive is checked before anything is deleted, and
    the flush, the load, the count check and re-applying the withdrawal ledgers (this
    installation's and the archive's) run in one transaction: a failure leaves the
    database as it was. Files are written where the settings put media; those of
    participants withdrawn again are deleted once it commits.
    """
    from studyplatform.actions.privacy import do_reapply_withdrawals

    if not archive_path.is_file():
        raise BackupError(f"There is no archive at {archive_path}.")
    roots = _roots()
    stages = {prefix: root.parent / f".restore-{prefix}" for prefix, root in roots.items()}
    try:
        with (
            tarfile.open(archive_path, "r:gz") as archive,
            tempfile.TemporaryDirectory() as scratch,
        ):
            manifest = _read_manifest(archive)
            empty = _database_is_empty()
            if not empty and not replace:
                raise BackupError(
                    "The database is not empty; restore with --replace to "
                    "delete what it holds first."
                )
            archive.extract("data.json", scratch, filter="data")
            data = Path(scratch) / "data.json"
            if file_sha256(data) != manifest["data_sha256"]:
                raise BackupError("data.json does not match its checksum: the archive is damaged.")
            staged = _stage_files(archive, manifest["files"], stages)
            try:
                known = ledger.merge(ledger.read(), _archived_ledger(archive, manifest))
            except ValueError as error:
                raise BackupError(
                    f"This installation's withdrawal ledger cannot be read "
                    f"({error}); nothing was changed."
                ) from None
            with transaction.atomic():
                if not empty:
                    call_command("flush", interactive=False, verbosity=0)
                call_command("loaddata", str(data), verbosity=0)
                counts = _counts()
                differing = {
                    label: (counts.get(label), expected)
                    for label, expected in manifest["counts"].items()
                    if counts.get(label) != expected
                }
                if differing:
                    raise BackupError(f"Restored row counts differ from the backup's: {differing}.")
                # The files are in place before the commit deletes those withdrawn again.
                size = _place_files(staged, roots)
                reapplied = do_reapply_withdrawals(known)
        ledger.rewrite(known)
    finally:
        for stage in stages.values():
            shutil.rmtree(stage, ignore_errors=True)
    return BackupSummary(
        rows=sum(counts.values()),
        files=len(staged),
        bytes=size,
        withdrawn_again=reapplied.participants,
    )


def _place_files(staged: dict[str, Path], roots: dict[str, Path]) -> int:
    """Move the staged files to their media roots; return their bytes."""
    size = 0
    for name, path in staged.items():
        prefix, _, relative = name.partition("/")
        target = roots[prefix] / relative
        target.parent.mkdir(parents=True, exist_ok=True)
        path.replace(target)
        size += target.stat().st_size
    return size


def _stage_files(archive: tarfile.TarFile, files: dict[str, str], stages: dict[str, Path]):
    """Extract every file beside its media root and check it; return the staged paths."""
    staged = {}
    for name, digest in files.items():
        prefix = name.partition("/")[0]
        if prefix not in stages:
            raise BackupError(f"The archive names a file outside the media roots: {name}.")
        try:
            archive.extract(archive.getmember(name), stages[prefix], filter="data")
        except (KeyError, tarfile.FilterError) as error:
            raise BackupError(f"{name} cannot be restored ({error}).") from None
        path = stages[prefix] / name
        if file_sha256(path) != digest:
            raise BackupError(f"{name} does not match its checksum: the archive is damaged.")
        staged[name] = path
    return staged
