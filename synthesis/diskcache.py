"""The engine's disk cache: arrays that take seconds to compute, kept between processes.

Built avatars (:mod:`synthesis.avatar.store`) and solved letters of the alphabet
(:mod:`synthesis.fingerspelling.alphabet`) are deterministic results of the engine's
files and a few libraries; every render process computed them again. Each is kept in
one ``.npz`` whose name carries :func:`synthesis.identity.code_digest`, the
versions of the libraries that compute it and the CPU kernels they run
(:func:`kernels_digest`), so that any change to these names a new file and a stale
result is never loaded. The directory is ``$SIGNSTUDY_AVATAR_CACHE``
(its name from when it held avatars only), else ``$XDG_CACHE_HOME/signstudy/avatars``,
else ``~/.cache/signstudy/avatars``; ``SIGNSTUDY_AVATAR_CACHE=off`` computes every time.
An unreadable file is computed again and replaced; a directory that cannot be written
only costs the time.
"""

import contextlib
import hashlib
import os
import tempfile
import zipfile
from collections.abc import Callable
from functools import cache
from importlib import metadata
from pathlib import Path
from typing import TypeVar

import numpy as np

from synthesis.identity import code_digest

CACHE_ENV = "SIGNSTUDY_AVATAR_CACHE"
T = TypeVar("T")


def cache_directory() -> Path | None:
    """Return the directory results are kept in, or None when caching is off."""
    chosen = os.environ.get(CACHE_ENV)
    if chosen is not None:
        return None if chosen.strip().lower() in ("", "off", "0", "no") else Path(chosen)
    base = os.environ.get("XDG_CACHE_HOME") or Path.home() / ".cache"
    return Path(base) / "signstudy" / "avatars"


@cache
def libraries_digest(libraries: tuple[str, ...]) -> str:
    """Return 8 hex digits naming the installed versions of *libraries*."""
    versions = []
    for name in libraries:
        try:
            versions.append(f"{name}=={metadata.version(name)}")
        except metadata.PackageNotFoundError:
            versions.append(f"{name} missing")
    return hashlib.sha256(";".join(versions).encode()).hexdigest()[:8]


# The environment variables that choose numpy's and OpenBLAS's kernels over the CPU's own.
KERNEL_ENVIRONMENT = ("NPY_DISABLE_CPU_FEATURES", "NPY_ENABLE_CPU_FEATURES", "OPENBLAS_CORETYPE")


@cache
def kernels_digest() -> str:
    """Return 8 hex digits naming the CPU kernels numpy and OpenBLAS run here.

    The same code and libraries give results that differ in the last bits on CPUs with
    other vector units (AVX2 or AVX-512), and an optimiser can follow those bits far: a
    GPLVM cached by an unpinned run on an AVX-512 machine put G and Y farthest apart
    where scripts/docs_figures.py's run, pinned to AVX2 kernels, puts G and J. The
    kernels follow numpy's enabled CPU features and the variables that override them.
    """
    try:
        from numpy._core._multiarray_umath import __cpu_features__
    except ImportError:  # numpy moved its private table: the variables still name a choice
        __cpu_features__ = {}
    enabled = sorted(name for name, on in __cpu_features__.items() if on)
    chosen = [f"{name}={os.environ.get(name, '')}" for name in KERNEL_ENVIRONMENT]
    return hashlib.sha256(";".join(enabled + chosen).encode()).hexdigest()[:8]


def cache_path(key: str, libraries: tuple[str, ...]) -> Path | None:
    """Return where the result named *key*, computed with *libraries*, is kept (None:
    caching is off)."""
    directory = cache_directory()
    if directory is None:
        return None
    digests = f"{code_digest()}-{libraries_digest(libraries)}-{kernels_digest()}"
    return directory / f"{key}-{digests}.npz"


def load_arrays(path: Path | None) -> dict[str, np.ndarray] | None:
    """Return the arrays kept at *path*, or None when there are none or they are unreadable."""
    if path is None:
        return None
    try:
        with np.load(path, allow_pickle=False) as stored:
            return {name: stored[name] for name in stored.files}
    except (OSError, KeyError, ValueError, zipfile.BadZipFile):
        return None


def save_arrays(path: Path | None, arrays: dict[str, np.ndarray]) -> None:
    """Keep *arrays* at *path* atomically (a reader never sees half a file); a directory
    that cannot be written is ignored."""
    if path is None:
        return
    with contextlib.suppress(OSError):
        path.parent.mkdir(parents=True, exist_ok=True)
        handle, temporary = tempfile.mkstemp(dir=path.parent, suffix=".tmp")
        try:
            with os.fdopen(handle, "wb") as stream:
                np.savez(stream, **arrays)
            os.replace(temporary, path)
        except BaseException:
            Path(temporary).unlink(missing_ok=True)
            raise


def cached(
    key: str,
    libraries: tuple[str, ...],
    compute: Callable[[], T],
    encode: Callable[[T], dict[str, np.ndarray]],
    decode: Callable[[dict[str, np.ndarray]], T],
) -> T:
    """Return the result kept under *key* (computed with *libraries*), decoded from its
    arrays; else compute it and keep its arrays. A file that does not decode (KeyError,
    ValueError: written by something else) is computed again and replaced."""
    path = cache_path(key, libraries)
    stored = load_arrays(path)
    if stored is not None:
        try:
            return decode(stored)
        except (KeyError, ValueError):
            pass
    result = compute()
    save_arrays(path, encode(result))
    return result
