"""Drive an imported humanoid avatar with the engine's motion: bone mapping, retargeting.

An imported avatar's joints are named to the engine's canonical joints by, in order:
its VRM humanoid bones (``VRMC_vrm``/``VRM``), the engine's own names (an avatar the
engine exported), then the naming conventions :func:`synthesis.skeleton.mapping.
detect_mapping` knows (Mixamo/HumanIK, Xsens, Blender, CMU), then the researcher's own
mapping saved in the file (``asset.extras.signstudy``). The engine poses its rig as
always; :class:`ImportedRig` turns each pose onto the imported skeleton
(:func:`synthesis.rigs.retarget.transfer_pose`: rest poses aligned limb by limb, each
mapped bone turning as the engine's does, bone lengths the avatar's), and the face's
channels play the avatar's morph targets that share the engine's blendshape names
(ARKit) or stand for them (VRM expressions).
"""

from dataclasses import dataclass

import numpy as np

from synthesis.avatar.imported.gltf_avatar import ImportedAvatar
from synthesis.avatar.imported.gltf_read import GltfError
from synthesis.avatar.model import Avatar, SkinnedPart
from synthesis.avatar.skinning import MorphDrive, Morphs, SkinWeights
from synthesis.rigs.retarget import transfer_pose
from synthesis.skeleton.kinematics import Pose, local_transforms
from synthesis.skeleton.mapping import detect_mapping
from synthesis.skeleton.skeleton import Joint, Skeleton

_DIGITS = ("thumb", "index", "middle", "ring", "pinky")
_VRM_TRUNK = {
    "hips": "hips",
    "spine": "spine_lower",
    "chest": "spine_middle",
    "upperChest": "spine_upper",
    "neck": "neck",
    "head": "head",
    "jaw": "jaw",
}


def _vrm_table(thumb_metacarpal: bool) -> dict[str, str]:
    """Return VRM humanoid bone → engine joint (VRM 1.0 names its thumb's first bone
    Metacarpal; 0.x calls the same three Proximal, Intermediate, Distal)."""
    table = dict(_VRM_TRUNK)
    for side in ("left", "right"):
        table.update(
            {
                f"{side}Eye": f"{side}_eye",
                f"{side}Shoulder": f"{side}_clavicle",
                f"{side}UpperArm": f"{side}_shoulder",
                f"{side}LowerArm": f"{side}_elbow",
                f"{side}Hand": f"{side}_wrist",
            }
        )
        thumb = (
            ("Metacarpal", "Proximal", "Distal")
            if thumb_metacarpal
            else ("Proximal", "Intermediate", "Distal")
        )
        for segment, joint in zip(thumb, ("cmc", "mcp", "ip"), strict=True):
            table[f"{side}Thumb{segment}"] = f"{side}_thumb_{joint}"
        for digit in _DIGITS[1:]:
            name = "Little" if digit == "pinky" else digit.capitalize()
            for segment, joint in zip(
                ("Proximal", "Intermediate", "Distal"), ("mcp", "pip", "dip"), strict=True
            ):
                table[f"{side}{name}{segment}"] = f"{side}_{digit}_{joint}"
    return table


def finger_joints(side: str) -> tuple[str, ...]:
    """Return the engine joints a hand must have to fingerspell: wrist and 15 finger joints."""
    joints = [f"{side}_wrist"]
    for digit in _DIGITS:
        ends = ("cmc", "mcp", "ip") if digit == "thumb" else ("mcp", "pip", "dip")
        joints += [f"{side}_{digit}_{end}" for end in ends]
    return tuple(joints)


def _skeleton(avatar: ImportedAvatar) -> Skeleton:
    """Return the avatar's skeleton with offsets from its bind pose (metres)."""
    offsets = local_transforms(avatar.parents, avatar.bind)[1][0]
    joints = []
    for name, parent, offset in zip(avatar.joint_names, avatar.parents, offsets, strict=True):
        channels = ("Xposition", "Yposition", "Zposition") if parent < 0 else ()
        joints.append(
            Joint(
                name,
                int(parent),
                tuple(float(v) for v in offset),
                (*channels, "Zrotation", "Xrotation", "Yrotation"),
            )
        )
    return Skeleton(tuple(joints), length_unit="m")


def bone_mapping(avatar: ImportedAvatar, engine_names) -> dict[str, str]:
    """Return the avatar's joint → engine joint names (see the module's order)."""
    engine_names = set(engine_names)
    mapping: dict[str, str] = {}
    if avatar.humanoid:
        table = _vrm_table(any("ThumbMetacarpal" in bone for bone in avatar.humanoid))
        mapping = {joint: table[bone] for bone, joint in avatar.humanoid.items() if bone in table}
    else:
        mapping = {name: name for name in avatar.joint_names if name in engine_names}
        if len(mapping) < 4:
            try:
                found = detect_mapping(_skeleton(avatar)).to_canonical
            except ValueError:
                found = {}
            mapping = {**found, **mapping}
    mapping.update(avatar.bones)
    return {joint: engine for joint, engine in mapping.items() if engine}


@dataclass(frozen=True, eq=False)
class ImportedRig:
    """The engine's rig driving an imported skeleton: ``pose(dofs)`` poses the engine's
    rig and turns that pose onto the avatar's joints."""

    engine: object
    skeleton: Skeleton
    pairs: dict[int, int]
    engine_rest: Pose
    rest: Pose
    kind: str = "imported"

    def pose(self, dofs_rad: np.ndarray) -> Pose:
        """Return the avatar's global joint transforms for the engine's DOF vectors."""
        source = self.engine.pose(np.atleast_2d(dofs_rad))
        return transfer_pose(
            source,
            self.engine_rest,
            self.engine.skeleton.parents,
            self.pairs,
            self.skeleton.parents,
            self.rest,
        )

    def neutral(self) -> np.ndarray:
        return self.engine.neutral()

    def clip(self, dofs_rad: np.ndarray) -> np.ndarray:
        return self.engine.clip(dofs_rad)


def _engine_name(canonical: str, engine_names: set[str], side: str) -> str | None:
    """Return the engine rig's joint for a canonical name (a hand rig drops the side)."""
    if canonical in engine_names:
        return canonical
    bare = canonical.removeprefix(f"{side}_")
    return bare if bare != canonical and bare in engine_names else None


def _morphs(mesh, drive_names: tuple[str, ...]) -> Morphs | None:
    """Return the mesh's morph targets the engine's face drives, as blendshapes."""
    names = [n for n in mesh.targets if n in drive_names]
    if not names:
        return None
    offsets = np.stack([mesh.targets[n] for n in names])
    moved = np.flatnonzero(np.abs(offsets).max(axis=(0, 2)) > 0)
    normals = np.stack([mesh.target_normals.get(n, np.zeros_like(mesh.targets[n])) for n in names])
    return Morphs(tuple(names), moved, offsets[:, moved], normals[:, moved])


def engine_avatar(
    imported: ImportedAvatar,
    engine_rig,
    engine_rest: Pose,
    drive: MorphDrive | None,
    side: str = "right",
) -> Avatar:
    """Return the engine avatar of *imported*, driven by *engine_rig*'s DOFs.

    *engine_rest* is the engine's pose the avatar's bind pose is aligned to (the
    engine avatar's own bind pose); *drive* the engine face's blendshape drive, whose
    names the avatar's morph targets may share. Raise GltfError when fewer than four
    joints map onto the engine's.
    """
    engine_names = set(engine_rig.skeleton.names)
    mapping = bone_mapping(imported, engine_names)
    skeleton = _skeleton(imported)
    index = {name: k for k, name in enumerate(imported.joint_names)}
    pairs = {}
    for joint, canonical in mapping.items():
        engine = _engine_name(canonical, engine_names, side)
        if joint in index and engine is not None:
            pairs[index[joint]] = engine_rig.skeleton.index(engine)
    if len(pairs) < 4:
        raise GltfError(
            f"Only {len(pairs)} of the avatar's joints map onto the engine's skeleton "
            f"({', '.join(imported.joint_names[:6])}, …): name them in the bone mapping."
        )
    rig = ImportedRig(engine_rig, skeleton, pairs, engine_rest, imported.bind)
    names = drive.names if drive is not None else ()
    parts = tuple(
        SkinnedPart(
            mesh.name,
            mesh.vertices_m,
            mesh.faces,
            mesh.colors_rgb,
            SkinWeights(mesh.joints, mesh.weights, mesh.main_joints),
            normals=mesh.normals,
            edge_m=mesh.edge_m,
            across_rgb=mesh.across_rgb,
            casts_shadow=mesh.casts_shadow,
            morphs=_morphs(mesh, names),
        )
        for mesh in imported.meshes
    )
    used = tuple(dict.fromkeys(n for part in parts if part.morphs for n in part.morphs.names))
    if used and drive is not None:
        rows = [drive.names.index(n) for n in used]
        drive = MorphDrive(used, drive.rising[rows], drive.falling[rows], drive.limits[rows])
    else:
        drive = None
    return Avatar(imported.name, rig, engine_rig.neutral(), parts, drive, bind=imported.bind)


def missing_joints(mapping: dict[str, str], side: str) -> list[str]:
    """Return the engine joints fingerspelling needs that *mapping* (the avatar's
    :func:`bone_mapping`) leaves out (a hand rig's names drop the side)."""
    mapped = set(mapping.values())
    return [
        joint
        for joint in finger_joints(side)
        if joint not in mapped and joint.removeprefix(f"{side}_") not in mapped
    ]


# The arm joints signing turns: one the avatar's mapping leaves out stays as the avatar
# was modelled while the rest signs (issue 54: 14 main bones renamed gave "45 joints
# mapped" and both arms held out in the T-pose, with no word of it).
SIGNING_BODY = tuple(
    f"{side}_{joint}" for side in ("right", "left") for joint in ("shoulder", "elbow", "wrist")
)


def missing_body_joints(mapping: dict[str, str]) -> list[str]:
    """Return the engine's signing arm joints (:data:`SIGNING_BODY`) *mapping* leaves out."""
    mapped = set(mapping.values())
    return [joint for joint in SIGNING_BODY if joint not in mapped]


def describe_avatar(imported: ImportedAvatar, engine_rig, drive: MorphDrive | None) -> dict:
    """Return what the engine makes of an imported avatar: its joints mapped and not,
    the arm joints signing turns that it lacks, the finger bones each hand lacks for
    fingerspelling, the face channels it plays."""
    mapping = bone_mapping(imported, engine_rig.skeleton.names)
    names = set(drive.names) if drive is not None else set()
    return {
        "joints": len(imported.joint_names),
        "mapped": {joint: mapping[joint] for joint in imported.joint_names if joint in mapping},
        "unmapped": [joint for joint in imported.joint_names if joint not in mapping],
        "missing_fingers": {side: missing_joints(mapping, side) for side in ("right", "left")},
        "missing_body": missing_body_joints(mapping),
        "face_channels": [name for name in imported.morph_names if name in names],
        "morph_targets": len(imported.morph_names),
        "height_m": round(imported.height_m, 3),
        "meta": {k: v for k, v in imported.meta.items() if isinstance(v, str | list)},
    }
