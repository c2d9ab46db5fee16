"""Keep built avatars on disk, keyed by the engine's digest, so a process loads them.

Building an avatar's skin (meshing its primitives, simplifying, weighting) takes
seconds, and every render process did it again. A built avatar's arrays are stored in
one ``.npz`` per avatar and build settings in the engine's disk cache
(:mod:`synthesis.diskcache`: named by the engine's digest and the meshing libraries'
versions, so a stale mesh is never loaded; ``SIGNSTUDY_AVATAR_CACHE=off`` builds every
time). An unreadable file is built again and replaced.
"""

from collections.abc import Callable

import numpy as np

from synthesis.avatar.model import Avatar, SkinnedPart
from synthesis.avatar.skinning import SkinWeights
from synthesis.diskcache import CACHE_ENV, cache_directory, cached

__all__ = ["CACHE_ENV", "MESH_LIBRARIES", "cache_directory", "cached_avatar"]

# The libraries that mesh, simplify and weight a skin: another version may build another.
MESH_LIBRARIES = ("numpy", "scipy", "scikit-image", "trimesh", "fast-simplification")
_FIELDS = ("vertices_m", "faces", "colors_rgb", "normals")
_OPTIONAL_FIELDS = ("edge_m", "across_rgb")


def cached_avatar(key: str, rig, build: Callable[[], Avatar]) -> Avatar:
    """Return the avatar stored under *key* for this engine, built by *build* if it is not
    there (and then stored). *rig* is the avatar's rig (not stored: it is code)."""
    return cached(key, MESH_LIBRARIES, build, _arrays, lambda stored: _avatar(stored, rig))


def _arrays(avatar: Avatar) -> dict[str, np.ndarray]:
    """Return *avatar*'s arrays, as stored."""
    arrays = {"name": np.array(avatar.name), "bind_dofs_rad": avatar.bind_dofs_rad,
              "part_names": np.array([part.name for part in avatar.parts]),
              "casts_shadow": np.array([part.casts_shadow for part in avatar.parts])}  # fmt: skip
    for k, part in enumerate(avatar.parts):
        for field in _FIELDS:
            arrays[f"{k}.{field}"] = np.asarray(getattr(part, field))
        for field in _OPTIONAL_FIELDS:
            if getattr(part, field) is not None:
                arrays[f"{k}.{field}"] = np.asarray(getattr(part, field))
        arrays[f"{k}.joints"], arrays[f"{k}.weights"] = part.weights.joints, part.weights.weights
    return arrays


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
        )
        for k, name in enumerate(stored["part_names"])
    )
    return Avatar(str(stored["name"]), rig, stored["bind_dofs_rad"], parts)
