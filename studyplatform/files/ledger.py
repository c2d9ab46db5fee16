"""Keep the withdrawal ledger: an append-only file of every withdrawal, outside the database.

A withdrawal deletes a participant's data for good, so it must survive what replaces the
database: restoring a backup made before it. Each withdrawal is appended here once it
commits (one JSON object a line: the participant's number and study, a SHA-256 of their
token, when, by whom, what went), backups carry a copy, and a restore applies every
withdrawal the ledger knows to the data it brings back (:mod:`studyplatform.management.backup`).
The token's hash recognises the participant without keeping anything that reaches them.
"""

import hashlib
import json
import os
from dataclasses import asdict, dataclass
from pathlib import Path

from django.conf import settings


@dataclass(frozen=True)
class LedgerEntry:
    """One withdrawal as the ledger records it (nothing personal)."""

    study_id: int
    participant_number: int
    token_sha256: str
    withdrawn_at: str
    withdrawn_by: str | None
    reason: str
    responses: int
    events: int
    personal_answers: int
    files: int


def token_sha256(token: str) -> str:
    """Return the hash by which the ledger knows a participant's token."""
    return hashlib.sha256(token.encode()).hexdigest()


def ledger_path() -> Path:
    """Return where this installation keeps its ledger (``SIGNSTUDY_WITHDRAWAL_LEDGER``)."""
    return Path(settings.SIGNSTUDY_WITHDRAWAL_LEDGER)


def append(entry: LedgerEntry, path: Path | None = None) -> None:
    """Append *entry* to the ledger and flush it to disk."""
    path = path or ledger_path()
    path.parent.mkdir(parents=True, exist_ok=True)
    line = json.dumps(asdict(entry), sort_keys=True) + "\n"
    fd = os.open(path, os.O_WRONLY | os.O_APPEND | os.O_CREAT, 0o600)
    with os.fdopen(fd, "a", encoding="utf-8") as handle:
        handle.write(line)
        handle.flush()
        os.fsync(handle.fileno())


def parse(text: str, source: str) -> list[LedgerEntry]:
    """Return the entries of ledger *text*; ValueError naming *source* and the line if bad."""
    entries = []
    for number, line in enumerate(text.splitlines(), 1):
        if not line.strip():
            continue
        try:
            entries.append(LedgerEntry(**json.loads(line)))
        except (ValueError, TypeError) as error:
            raise ValueError(f"{source}, line {number}: not a withdrawal ({error}).") from None
    return entries


def read(path: Path | None = None) -> list[LedgerEntry]:
    """Return every entry of the ledger at *path* (none if there is no ledger yet)."""
    path = path or ledger_path()
    try:
        text = path.read_text(encoding="utf-8")
    except FileNotFoundError:
        return []
    return parse(text, str(path))


def merge(*ledgers: list[LedgerEntry]) -> list[LedgerEntry]:
    """Return the entries of all *ledgers*, each withdrawal once, oldest first."""
    seen: dict[str, LedgerEntry] = {}
    for entries in ledgers:
        for entry in entries:
            seen.setdefault(entry.token_sha256, entry)
    return sorted(seen.values(), key=lambda e: (e.withdrawn_at, e.participant_number))


def rewrite(entries: list[LedgerEntry], path: Path | None = None) -> None:
    """Replace the ledger with *entries* (atomically: a crash leaves the old or the new)."""
    path = path or ledger_path()
    path.parent.mkdir(parents=True, exist_ok=True)
    temporary = path.with_name(path.name + ".new")
    fd = os.open(temporary, os.O_WRONLY | os.O_CREAT | os.O_TRUNC, 0o600)
    with os.fdopen(fd, "w", encoding="utf-8") as handle:
        handle.writelines(json.dumps(asdict(e), sort_keys=True) + "\n" for e in entries)
        handle.flush()
        os.fsync(handle.fileno())
    temporary.replace(path)
