"""Read a VRM file's parts: humanoid bones, meta, and preset expressions as blendshapes.

VRM 1.0 keeps them in the ``VRMC_vrm`` extension, VRM 0.x in ``VRM`` (which faces −Z).
Each part is checked to be the JSON type the specification gives it, so a malformed
file is refused naming the part (issue 51: a humanoid given as a list, a bone as a
string, a weight as text raised AttributeError and ValueError).
"""

from dataclasses import replace

import numpy as np

from synthesis.avatar.imported.gltf_read import GltfError


def _object(value, what: str) -> dict:
    """Return *value*, a JSON object of a VRM extension (absent: empty); GltfError
    naming *what* when it is anything else."""
    if value is None:
        return {}
    if not isinstance(value, dict):
        raise GltfError(f"The VRM {what} is not an object.")
    return value


def _list(value, what: str) -> list:
    if value is None:
        return []
    if not isinstance(value, list):
        raise GltfError(f"The VRM {what} is not a list.")
    return value


def vrm_humanoid(gltf) -> tuple[dict, dict, bool]:
    """Return a VRM file's humanoid bones (VRM name → node), meta, and whether it is
    VRM 0.x (facing −Z); empty for plain glTF. GltfError names a malformed part."""
    extensions = _object(gltf.extensions, "extensions")
    if "VRMC_vrm" in extensions:
        vrm = _object(extensions["VRMC_vrm"], "extension VRMC_vrm")
        humanoid = _object(vrm.get("humanoid"), "humanoid")
        entries = _object(humanoid.get("humanBones"), "humanBones").items()
        bones = {str(name): _object(bone, f"bone {name}").get("node") for name, bone in entries}
        return bones, dict(_object(vrm.get("meta"), "meta")), False
    if "VRM" in extensions:
        vrm = _object(extensions["VRM"], "extension VRM")
        humanoid = _object(vrm.get("humanoid"), "humanoid")
        listed = _list(humanoid.get("humanBones"), "humanBones")
        entries = [_object(bone, "humanBones entry") for bone in listed]
        bones = {str(bone.get("bone")): bone.get("node") for bone in entries}
        return bones, dict(_object(vrm.get("meta"), "meta")), True
    return {}, {}, False


# VRM's preset expressions, as the engine's face drives them: the ARKit blendshape whose
# channel each stands for (VRM 1.0 names; 0.x's presets are read under the same names).
VRM_EXPRESSIONS = {
    "blink": "eyeBlinkLeft",
    "blinkLeft": "eyeBlinkLeft",
    "blinkRight": "eyeBlinkRight",
    "aa": "jawOpen",
    "ou": "mouthPucker",
    "oh": "mouthFunnel",
    "ee": "mouthStretchLeft",
    "ih": "mouthSmileRight",
    "happy": "mouthSmileLeft",
    "angry": "browDownLeft",
    "sad": "mouthFrownLeft",
    "surprised": "browInnerUp",
    "lookUp": "eyeLookUpLeft",
    "lookDown": "eyeLookDownLeft",
    "lookLeft": "eyeLookOutLeft",
    "lookRight": "eyeLookInLeft",
}
_VRM0_PRESETS = {
    "a": "aa",
    "i": "ih",
    "u": "ou",
    "e": "ee",
    "o": "oh",
    "joy": "happy",
    "sorrow": "sad",
    "fun": "happy",
    "blink_l": "blinkLeft",
    "blink_r": "blinkRight",
    "lookup": "lookUp",
    "lookdown": "lookDown",
    "lookleft": "lookLeft",
    "lookright": "lookRight",
}


def _weight(bind: dict, default: float) -> float:
    weight = bind.get("weight", default)
    if isinstance(weight, bool) or not isinstance(weight, int | float) or not np.isfinite(weight):
        raise GltfError("A VRM expression's weight is not a number.")
    return float(weight)


def _expression_binds(gltf) -> dict[str, list[tuple[tuple[str, int], int, float]]]:
    """Return each VRM preset expression's morph target binds by VRM 1.0 name: (what
    holds the target, its index, weight 0–1), the holder ("node", n) in VRM 1.0 and
    ("mesh", m) in 0.x. GltfError names a malformed part."""
    extensions = _object(gltf.extensions, "extensions")
    binds = {}
    if "VRMC_vrm" in extensions:
        vrm = _object(extensions["VRMC_vrm"], "extension VRMC_vrm")
        expressions = _object(vrm.get("expressions"), "expressions")
        for name, expression in _object(expressions.get("preset"), "preset").items():
            expression = _object(expression, f"expression {name}")
            bound = _list(expression.get("morphTargetBinds"), "morphTargetBinds")
            binds[str(name)] = [
                (("node", bind.get("node")), bind.get("index"), _weight(bind, 1.0))
                for bind in (_object(b, "morphTargetBind") for b in bound)
            ]
    elif "VRM" in extensions:
        vrm = _object(extensions["VRM"], "extension VRM")
        master = _object(vrm.get("blendShapeMaster"), "blendShapeMaster")
        for group in _list(master.get("blendShapeGroups"), "blendShapeGroups"):
            group = _object(group, "blendShapeGroup")
            preset = str(group.get("presetName") or "").lower()
            binds[_VRM0_PRESETS.get(preset, preset)] = [
                (("mesh", bind.get("mesh")), bind.get("index"), _weight(bind, 100) / 100)
                for bind in (_object(b, "bind") for b in _list(group.get("binds"), "binds"))
            ]
    return binds


def with_expressions(gltf, meshes: list, nodes: list[int]) -> list:
    """Return *meshes* with each VRM preset expression as a blendshape named by the
    ARKit shape the face drives for it (where the file has no such target itself)."""
    binds = _expression_binds(gltf)
    if not binds:
        return meshes
    out = []
    for mesh, node in zip(meshes, nodes, strict=True):
        names, targets = list(mesh.targets), dict(mesh.targets)
        holders = {("node", node), ("mesh", gltf.nodes[node].mesh)}
        for expression, bound in binds.items():
            arkit = VRM_EXPRESSIONS.get(expression)
            if arkit is None or arkit in targets:
                continue
            offsets = np.zeros_like(mesh.vertices_m)
            for holder, index, weight in bound:
                usable = isinstance(holder[1], int) and isinstance(index, int)
                if usable and holder in holders and 0 <= index < len(names):
                    offsets += weight * mesh.targets[names[index]]
            if np.abs(offsets).max(initial=0.0) > 0:
                targets[arkit] = offsets
        out.append(replace(mesh, targets=targets))
    return out
