"""Load an imported avatar file for a view, once a process: the engine avatar a clip
is filmed with when its ``avatar_file`` is set (:func:`synthesis.avatar.looks.avatar_for`)."""

import functools
from pathlib import Path

import numpy as np

from synthesis.avatar.imported.gltf_avatar import read_gltf_avatar
from synthesis.avatar.imported.gltf_read import GltfError
from synthesis.avatar.imported.humanoid import (
    bone_mapping,
    engine_avatar,
    missing_body_joints,
    missing_joints,
)
from synthesis.identity import file_sha256


@functools.lru_cache(maxsize=8)
def _imported(sha256: str, path: str):
    del sha256  # the cache key: the same path with new content reads again
    return read_gltf_avatar(Path(path).read_bytes(), Path(path).name)


@functools.lru_cache(maxsize=8)
def _avatar(sha256: str, path: str, view: str, side: str, builtin):
    """Return the engine avatar of the file (made once a process per file, view and
    built-in avatar, which hashes by identity: the built-in ones are made once a process).

    *builtin* is the engine's own signer of the view: its rig's DOFs drive the import,
    its bind pose is what the import's is aligned to, its face drive plays the
    blendshapes they share.
    """
    return engine_avatar(
        _imported(sha256, path), builtin.rig, builtin.bind_pose, builtin.drive, side
    )


def _existing(path: str | Path) -> tuple[str, str]:
    path = str(path)
    if not Path(path).is_file():
        raise GltfError(f"No avatar file at {path}.")
    return file_sha256(path), path


def imported_avatar(path: str | Path, view: str, side: str, builtin):
    """Return the engine avatar of the glTF/VRM file at *path* for *view* and *side*,
    driven as the engine's *builtin* avatar of that view; GltfError names the problem
    (see :func:`read_gltf_avatar`)."""
    return _avatar(*_existing(path), view, side, builtin)


def check_fingers(path: str | Path, side: str) -> None:
    """Raise GltfError if the avatar's *side* hand lacks a bone fingerspelling moves.

    Sentences play on such an avatar (its hands keep their rest shape); words do not.
    """
    from synthesis.rigs.body import BodyModel

    sha256, path = _existing(path)
    imported = _imported(sha256, path)
    missing = missing_joints(bone_mapping(imported, BodyModel(side).skeleton.names), side)
    if missing:
        raise GltfError(
            f"{Path(path).name} has no {', '.join(missing[:4])}"
            f"{' …' if len(missing) > 4 else ''} bone: its {side} hand cannot "
            "fingerspell (sentences without fingerspelling can use it)."
        )


def check_body(path: str | Path) -> None:
    """Raise GltfError if the avatar's mapping misses an arm joint signing turns.

    Such a joint would stay as the avatar was modelled (a T-pose's arms held out) while
    the rest of the body signs.
    """
    from synthesis.rigs.body import BodyModel

    sha256, path = _existing(path)
    imported = _imported(sha256, path)
    missing = missing_body_joints(bone_mapping(imported, BodyModel("right").skeleton.names))
    if missing:
        raise GltfError(
            f"{Path(path).name}: no bone is mapped to the engine's {', '.join(missing)}, so "
            "they would stay as the avatar was modelled while the rest signs; map them "
            "(the avatar's page in the admin site)."
        )


def fitted_camera(camera, avatar):
    """Return the signing view's *camera* moved by as much as the imported *avatar*'s
    head stands from the engine signer's (the view framed for the engine's proportions
    would cut a shorter or taller signer's face)."""
    from dataclasses import replace

    rig = avatar.rig
    head = rig.engine.skeleton.index("head") if "head" in rig.engine.skeleton.names else None
    theirs = [j for j, e in rig.pairs.items() if e == head]
    if head is None or not theirs:
        return camera
    shift = rig.rest.positions_m[0, theirs[0]] - rig.engine_rest.positions_m[0, head]
    return replace(
        camera,
        eye_m=tuple(np.add(camera.eye_m, shift)),
        target_m=tuple(np.add(camera.target_m, shift)),
    )
