"""Keep built avatars on disk, keyed by the engine's digest, so a process loads them.

Building an avatar's skin (meshing its primitives, simplifying, weighting) takes
seconds, and every render process did it again. A built avatar's arrays are stored in
one ``.npz`` per avatar and build settings under the cache directory, its name carrying
:func:`synthesis.identity.engine_digest` and the meshing libraries' versions: any change
to the engine's files or those libraries names a new file, so a stale mesh is never
loaded. The directory is ``$SIGNSTUDY_AVATAR_CACHE``,
else ``$XDG_CACHE_HOME/signstudy/avatars``, else ``~/.cache/signstudy/avatars``;
``SIGNSTUDY_AVATAR_CACHE=off`` builds every time. An unreadable file is built again and
replaced; a directory that cannot be written only costs the time.
"""

import contextlib
import hashlib
import os
import tempfile
import zipfile
from collections.abc import Callable
from importlib import metadata
from pathlib import Path

import numpy as np

from synthesis.avatar.model import Avatar, SkinnedPart
from synthesis.avatar.skinning import SkinWeights
from synthesis.identity import engine_digest

CACHE_ENV = "SIGNSTUDY_AVATAR_CACHE"
# The libraries that mesh, simplify and weight a skin: another version may build another.
MESH_LIBRARIES = ("numpy", "scipy", "scikit-image", "trimesh", "fast-simplification")
_FIELDS = ("vertices_m", "faces", "colors_rgb", "normals")
_OPTIONAL_FIELDS = ("edge_m", "across_rgb")


def cache_directory() -> Path | None:
    """Return the directory avatars are kept in, or None when caching is off."""
    chosen = os.environ.get(CACHE_ENV)
    if chosen is not None:
        return None if chosen.strip().lower() in ("", "off", "0", "no") else Path(chosen)
    base = os.environ.get("XDG_CACHE_HOME") or Path.home() / ".cache"
    return Path(base) / "signstudy" / "avatars"


def cached_avatar(key: str, rig, build: Callable[[], Avatar]) -> Avatar:
    """Return the avatar stored under *key* for this engine, built by *build* if it is not
    there (and then stored). *rig* is the avatar's rig (not stored: it is code)."""
    directory = cache_directory()
    if directory is None:
        return build()
    path = directory / f"{key}-{engine_digest()}-{_libraries_digest()}.npz"
    try:
        return _load(path, rig)
    except (OSError, KeyError, ValueError, zipfile.BadZipFile):
        pass  # not there yet, or unreadable: build it again
    avatar = build()
    with contextlib.suppress(OSError):  # a read-only cache only costs the build time
        _save(avatar, path)
    return avatar


def _libraries_digest() -> str:
    """Return 8 hex digits naming the installed versions of MESH_LIBRARIES."""
    versions = []
    for name in MESH_LIBRARIES:
        try:
            versions.append(f"{name}=={metadata.version(name)}")
        except metadata.PackageNotFoundError:
            versions.append(f"{name} missing")
    return hashlib.sha256(";".join(versions).encode()).hexdigest()[:8]


def _save(avatar: Avatar, path: Path) -> None:
    """Write *avatar*'s arrays to *path* atomically (a reader never sees half a file)."""
    arrays = {"name": np.array(avatar.name), "bind_dofs_rad": avatar.bind_dofs_rad,
              "part_names": np.array([part.name for part in avatar.parts])}  # fmt: skip
    for k, part in enumerate(avatar.parts):
        for field in _FIELDS:
            arrays[f"{k}.{field}"] = np.asarray(getattr(part, field))
        for field in _OPTIONAL_FIELDS:
            if getattr(part, field) is not None:
                arrays[f"{k}.{field}"] = np.asarray(getattr(part, field))
        arrays[f"{k}.joints"], arrays[f"{k}.weights"] = part.weights.joints, part.weights.weights
    path.parent.mkdir(parents=True, exist_ok=True)
    handle, temporary = tempfile.mkstemp(dir=path.parent, suffix=".tmp")
    try:
        with os.fdopen(handle, "wb") as stream:
            np.savez(stream, **arrays)
        os.replace(temporary, path)
    except BaseException:
        Path(temporary).unlink(missing_ok=True)
        raise


def _load(path: Path, rig) -> Avatar:
    """Read an avatar written by :func:`_save`, with *rig* as its rig."""
    with np.load(path, allow_pickle=False) as stored:
        parts = tuple(
            SkinnedPart(
                str(name),
                *(stored[f"{k}.{field}"] for field in _FIELDS[:3]),
                SkinWeights(stored[f"{k}.joints"], stored[f"{k}.weights"]),
                stored[f"{k}.normals"],
                *(stored.get(f"{k}.{field}") for field in _OPTIONAL_FIELDS),
            )
            for k, name in enumerate(stored["part_names"])
        )
        return Avatar(str(stored["name"]), rig, stored["bind_dofs_rad"], parts)
