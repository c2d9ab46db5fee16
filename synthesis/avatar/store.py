"""Keep built avatars on disk, keyed by the engine's digest, so a process loads them.

Building an avatar's skin (meshing its primitives, simplifying, weighting) takes
seconds, and every render process did it again. A built avatar's arrays are stored in
one ``.npz`` per avatar and build settings in the engine's disk cache
(:mod:`synthesis.diskcache`: named by the engine's digest and the meshing libraries'
versions, so a stale mesh is never loaded; ``SIGNSTUDY_AVATAR_CACHE=off`` builds every
time). An unreadable file is built again and replaced.
"""

import dataclasses
from collections.abc import Callable

import numpy as np

from synthesis.avatar.model import Avatar, SkinnedPart
from synthesis.avatar.skinning import MorphDrive, Morphs, SkinWeights
from synthesis.diskcache import CACHE_ENV, cache_directory, cached

__all__ = ["CACHE_ENV", "MESH_LIBRARIES", "cache_directory", "cached_avatar"]

# The libraries that mesh, simplify and weight a skin: another version may build another.
MESH_LIBRARIES = ("numpy", "scipy", "scikit-image", "trimesh", "fast-simplification")
_FIELDS = ("vertices_m", "faces", "colors_rgb", "normals")
_OPTIONAL_FIELDS = ("edge_m", "across_rgb")
_MORPH_FIELDS = ("names", "vertices", "offsets_m", "normal_offsets")
_DRIVE_FIELDS = ("names", "rising", "falling", "limits")
# Rig fields an avatar's build may set from its mesh (the human's eyes): kept with it.
_RIG_FIELDS = ("eye_centre_m",)


def cached_avatar(
    key: str, rig, build: Callable[[], Avatar], libraries: tuple[str, ...] = MESH_LIBRARIES
) -> Avatar:
    """Return the avatar stored under *key* for this engine, built by *build* if it is not
    there (and then stored). *rig* is the avatar's rig (not stored: it is code; the
    fields in ``_RIG_FIELDS`` that the build set are stored and given back to it).
    *libraries* are those whose versions the build depends on."""
    return cached(key, libraries, build, _arrays, lambda stored: _avatar(stored, rig))


def _arrays(avatar: Avatar) -> dict[str, np.ndarray]:
    """Return *avatar*'s arrays, as stored."""
    arrays = {
        "name": np.array(avatar.name),
        "bind_dofs_rad": avatar.bind_dofs_rad,
        "part_names": np.array([part.name for part in avatar.parts]),
        "casts_shadow": np.array([part.casts_shadow for part in avatar.parts]),
    }
    for k, part in enumerate(avatar.parts):
        for field in _FIELDS:
            arrays[f"{k}.{field}"] = np.asarray(getattr(part, field))
        for field in _OPTIONAL_FIELDS:
            if getattr(part, field) is not None:
                arrays[f"{k}.{field}"] = np.asarray(getattr(part, field))
        arrays[f"{k}.joints"], arrays[f"{k}.weights"] = part.weights.joints, part.weights.weights
        if part.morphs is not None:
            for field in _MORPH_FIELDS:
                arrays[f"{k}.morphs.{field}"] = np.asarray(getattr(part.morphs, field))
    if avatar.drive is not None:
        for field in _DRIVE_FIELDS:
            arrays[f"drive.{field}"] = np.asarray(getattr(avatar.drive, field))
    for field in _RIG_FIELDS:
        if getattr(avatar.rig, field, None) is not None:
            arrays[f"rig.{field}"] = np.asarray(getattr(avatar.rig, field))
    return arrays


def _morphs(stored: dict, prefix: str, kind, fields) -> object | None:
    if f"{prefix}.names" not in stored:
        return None
    values = [stored[f"{prefix}.{field}"] for field in fields]
    return kind(tuple(str(name) for name in values[0]), *values[1:])


def _avatar(stored: dict[str, np.ndarray], rig) -> Avatar:
    """Return the avatar of arrays written by :func:`_arrays`, with *rig* as its rig."""
    parts = tuple(
        SkinnedPart(
            str(name),
            *(stored[f"{k}.{field}"] for field in _FIELDS[:3]),
            SkinWeights(stored[f"{k}.joints"], stored[f"{k}.weights"]),
            stored[f"{k}.normals"],
            *(stored.get(f"{k}.{field}") for field in _OPTIONAL_FIELDS),
            bool(stored["casts_shadow"][k]),
            _morphs(stored, f"{k}.morphs", Morphs, _MORPH_FIELDS),
        )
        for k, name in enumerate(stored["part_names"])
    )
    kept = {
        field: tuple(float(v) for v in stored[f"rig.{field}"])
        for field in _RIG_FIELDS
        if f"rig.{field}" in stored
    }
    if kept:
        rig = dataclasses.replace(rig, **kept)
    return Avatar(
        str(stored["name"]),
        rig,
        stored["bind_dofs_rad"],
        parts,
        _morphs(stored, "drive", MorphDrive, _DRIVE_FIELDS),
    )
