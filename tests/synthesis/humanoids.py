"""Build small humanoid GLB and VRM files for import tests: a box per bone, T-pose.

Made by this script (pygltflib through the engine's buffer builder), so no third-party
model is copied into the repository. Names follow Mixamo (``mixamorig:``-less HumanIK)
or, for the VRM file, VRoid's ``J_Bip_*`` with the bones named by ``VRMC_vrm``.
"""

import numpy as np
import pygltflib as gl

from synthesis.interchange.glb import FLOAT, UINT16, UINT32, BufferBuilder

# HumanIK name, parent, position (m) in T-pose, facing +Z; the character's left is +X.
TRUNK = [
    ("Hips", None, (0, 1.0, 0)),
    ("Spine", "Hips", (0, 1.1, 0)),
    ("Spine1", "Spine", (0, 1.22, 0)),
    ("Spine2", "Spine1", (0, 1.34, 0)),
    ("Neck", "Spine2", (0, 1.5, 0)),
    ("Head", "Neck", (0, 1.6, 0)),
]
VRM_NAMES = {
    "Hips": "hips",
    "Spine": "spine",
    "Spine1": "chest",
    "Spine2": "upperChest",
    "Neck": "neck",
    "Head": "head",
}
DIGITS = {
    "Thumb": (0.03, -0.01, 0.04),
    "Index": (0.09, 0, 0.03),
    "Middle": (0.095, 0, 0.01),
    "Ring": (0.09, 0, -0.01),
    "Pinky": (0.08, 0, -0.03),
}
VRM_DIGITS = {
    "Thumb": ("Metacarpal", "Proximal", "Distal"),
    "Index": "Index",
    "Middle": "Middle",
    "Ring": "Ring",
    "Pinky": "Little",
}


def bones(fingers: bool = True) -> list[tuple[str, str | None, tuple, str]]:
    """Return (name, parent, position, VRM bone name) of the humanoid's joints."""
    out = [(name, parent, position, VRM_NAMES[name]) for name, parent, position in TRUNK]
    for cap, sign in (("Left", 1.0), ("Right", -1.0)):
        lower = cap.lower()
        arm = [
            (f"{cap}Shoulder", "Spine2", (0.03 * sign, 1.45, 0), f"{lower}Shoulder"),
            (f"{cap}Arm", f"{cap}Shoulder", (0.17 * sign, 1.45, 0), f"{lower}UpperArm"),
            (f"{cap}ForeArm", f"{cap}Arm", (0.45 * sign, 1.45, 0), f"{lower}LowerArm"),
            (f"{cap}Hand", f"{cap}ForeArm", (0.70 * sign, 1.45, 0), f"{lower}Hand"),
        ]
        out += arm
        if not fingers:
            continue
        for digit, (dx, dy, dz) in DIGITS.items():
            segments = VRM_DIGITS[digit]
            if isinstance(segments, str):
                segments = tuple(f"{segments}{s}" for s in ("Proximal", "Intermediate", "Distal"))
            else:
                segments = tuple(f"Thumb{s}" for s in segments)
            parent = f"{cap}Hand"
            for k in range(3):
                x = 0.70 + dx + 0.03 * k * (1 if digit != "Thumb" else 0.7)
                name = f"{cap}Hand{digit}{k + 1}"
                out.append((name, parent, (x * sign, 1.45 + dy, dz), f"{lower}{segments[k]}"))
                parent = name
    return out


def _box(centre: np.ndarray, half: float) -> tuple[np.ndarray, np.ndarray]:
    corners = np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)], float)
    faces = np.array(
        [
            [0, 1, 3],
            [0, 3, 2],
            [4, 6, 7],
            [4, 7, 5],
            [0, 4, 5],
            [0, 5, 1],
            [2, 3, 7],
            [2, 7, 6],
            [0, 2, 6],
            [0, 6, 4],
            [1, 5, 7],
            [1, 7, 3],
        ]
    )
    return centre + half * corners, faces


def humanoid_glb(
    fingers: bool = True,
    vrm: bool = False,
    skin: bool = True,
    morphs: tuple[str, ...] = (),
    expressions: dict | None = None,
) -> bytes:
    """Return a T-posed humanoid as GLB (VRM 1.0 with *vrm*), a box skinned to each bone;
    *morphs* names morph targets that lift the head box; *expressions* (VRM preset →
    morph target index) binds VRM expressions to them; without *skin*, no skin at all."""
    joints = bones(fingers)
    names = [j[0] for j in joints]
    positions = {name: np.asarray(position, float) for name, _, position, _ in joints}
    gltf = gl.GLTF2(asset=gl.Asset(version="2.0", generator="tests/synthesis/humanoids.py"))
    buffer = BufferBuilder(gltf)
    for name, parent, _, _ in joints:
        offset = positions[name] - (positions[parent] if parent else 0.0)
        node_name = f"J_Bip_{name}" if vrm else name
        gltf.nodes.append(gl.Node(name=node_name, translation=offset.tolist()))
    for index, (_, parent, _, _) in enumerate(joints):
        if parent is not None:
            gltf.nodes[names.index(parent)].children.append(index)
    vertices, faces, bone = [], [], []
    for index, (name, _, _, _) in enumerate(joints):
        box, tris = _box(positions[name], 0.012 if "Hand" in name and name[-1].isdigit() else 0.04)
        faces.append(tris + 8 * index)
        vertices.append(box)
        bone += [index] * 8
    vertices, faces = np.concatenate(vertices), np.concatenate(faces)
    attributes = gl.Attributes(POSITION=buffer.add(vertices, FLOAT, gl.ARRAY_BUFFER, bounds=True))
    if skin:
        attributes.JOINTS_0 = buffer.add(
            np.column_stack([bone, np.zeros((len(bone), 3))]), UINT16, gl.ARRAY_BUFFER
        )
        weights = np.zeros((len(bone), 4))
        weights[:, 0] = 1.0
        attributes.WEIGHTS_0 = buffer.add(weights, FLOAT, gl.ARRAY_BUFFER)
    primitive = gl.Primitive(
        attributes=attributes,
        indices=buffer.add(faces.reshape(-1, 1), UINT32, gl.ELEMENT_ARRAY_BUFFER),
    )
    mesh = gl.Mesh(name="body", primitives=[primitive])
    head = names.index("Head")
    for _ in morphs:  # each lifts the head's box (names only tell them apart)
        offsets = np.zeros_like(vertices)
        offsets[8 * head : 8 * head + 8, 1] = 0.02
        primitive.targets.append({"POSITION": buffer.add(offsets, FLOAT, bounds=True)})
    if morphs:
        mesh.extras = {"targetNames": list(morphs)}
        mesh.weights = [0.0] * len(morphs)
    gltf.meshes.append(mesh)
    inverse = np.repeat(np.eye(4)[None], len(joints), axis=0)
    inverse[:, :3, 3] = -np.array([positions[n] for n in names])
    if skin:
        matrices = buffer.add(np.swapaxes(inverse, 1, 2).reshape(-1, 16), FLOAT)
        gltf.skins.append(
            gl.Skin(joints=list(range(len(joints))), skeleton=0, inverseBindMatrices=matrices)
        )
    gltf.nodes.append(gl.Node(name="body", mesh=0, skin=0 if skin else None))
    gltf.scenes.append(gl.Scene(nodes=[0, len(gltf.nodes) - 1]))
    gltf.scene = 0
    if vrm:
        gltf.extensionsUsed = ["VRMC_vrm"]
        gltf.extensions = {
            "VRMC_vrm": {
                "specVersion": "1.0",
                "meta": {
                    "name": "Tiny signer",
                    "authors": ["SignStudy tests"],
                    "licenseUrl": "https://vrm.dev/licenses/1.0/",
                },
                "humanoid": {
                    "humanBones": {
                        vrm_name: {"node": index}
                        for index, (_, _, _, vrm_name) in enumerate(joints)
                    }
                },
                "expressions": {
                    "preset": {
                        name: {
                            "morphTargetBinds": [
                                {"node": len(gltf.nodes) - 1, "index": index, "weight": 1.0}
                            ]
                        }
                        for name, index in (expressions or {}).items()
                    }
                },
            }
        }
    gltf.set_binary_blob(buffer.finish())
    return b"".join(gltf.save_to_bytes())
