"""Avatars researchers bring: humanoid glTF 2.0 / VRM files read, mapped and retargeted."""

from synthesis.avatar.imported.gltf_avatar import (
    ImportedAvatar,
    ImportedMesh,
    read_gltf_avatar,
    with_bone_mapping,
)
from synthesis.avatar.imported.gltf_read import GltfError
from synthesis.avatar.imported.humanoid import (
    ImportedRig,
    bone_mapping,
    describe_avatar,
    engine_avatar,
    finger_joints,
    missing_joints,
)
from synthesis.avatar.imported.load import check_fingers, fitted_camera, imported_avatar

__all__ = [
    "GltfError",
    "ImportedAvatar",
    "ImportedMesh",
    "ImportedRig",
    "bone_mapping",
    "check_fingers",
    "describe_avatar",
    "engine_avatar",
    "finger_joints",
    "fitted_camera",
    "imported_avatar",
    "missing_joints",
    "read_gltf_avatar",
    "with_bone_mapping",
]
