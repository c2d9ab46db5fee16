"""The engine's identity: a digest of its own source and data files.

Every clip's hash includes it, so a change to any engine file — code, alphabet, routes,
sign library, shaders — names every clip anew instead of reusing a cached one rendered
by other code. A hand-set version number could be forgotten; the files cannot.
"""

import hashlib
from functools import cache
from pathlib import Path

PACKAGE = Path(__file__).resolve().parent
IGNORED_DIRECTORIES = {"__pycache__"}
IGNORED_SUFFIXES = {".pyc", ".pyo"}


def engine_files(root: Path = PACKAGE) -> list[Path]:
    """Return the engine's files under *root* that shape a clip, in a fixed order."""
    return sorted(
        path
        for path in root.rglob("*")
        if path.is_file()
        and path.suffix not in IGNORED_SUFFIXES
        and not IGNORED_DIRECTORIES & set(path.relative_to(root).parts)
    )


@cache
def engine_digest(root: Path = PACKAGE) -> str:
    """Return the first 16 hex digits of the SHA-256 over every engine file's path and bytes."""
    digest = hashlib.sha256()
    for path in engine_files(root):
        digest.update(path.relative_to(root).as_posix().encode() + b"\0")
        digest.update(hashlib.sha256(path.read_bytes()).digest())
    return digest.hexdigest()[:16]


def file_sha256(path: str | Path) -> str:
    """Return the SHA-256 of a file's bytes, read a megabyte at a time."""
    digest = hashlib.sha256()
    with open(path, "rb") as handle:
        for block in iter(lambda: handle.read(1 << 20), b""):
            digest.update(block)
    return digest.hexdigest()
