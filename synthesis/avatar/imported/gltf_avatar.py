"""Read a humanoid glTF 2.0 / VRM avatar: its skeleton, skinned meshes and morph targets.

The skin's joints become a skeleton (parents first) whose bind pose is the inverse of
the skin's inverse bind matrices (scale dropped: the engine's poses are rigid); each
triangle primitive of a mesh that skin deforms becomes a skinned part with the file's
vertices, normals, the four strongest bone weights and its colours (vertex colours,
else the base colour texture sampled at each vertex, else the material's colour);
morph targets become blendshapes named by ``extras.targetNames`` (the common
convention, ARKit's names in the engine's own files). A VRM 1.0 file's humanoid bone
names and expressions come along (``VRMC_vrm``); a VRM 0.x file (extension ``VRM``),
which faces −Z, is turned to face +Z as glTF and the engine do.
"""

import io
from dataclasses import dataclass, field, replace

import numpy as np
from scipy.spatial.transform import Rotation

from synthesis.avatar.colour import linear_to_srgb, srgb_to_linear
from synthesis.avatar.imported.gltf_read import (
    COLOR_ACROSS,
    COLOR_INSIDE,
    DAMAGE,
    EDGE,
    MAIN_JOINT,
    GltfError,
    Reader,
    damaged,
    load,
)
from synthesis.avatar.imported.vrm import vrm_humanoid, with_expressions
from synthesis.skeleton.kinematics import Pose

TRIANGLES = 4
# How tall a humanoid may stand in metres: outside this, the file's unit is not metres.
HEIGHT_RANGE_M = (0.1, 3.5)  # a hand and forearm alone, up to a giant


@dataclass(frozen=True, eq=False)
class ImportedMesh:
    """One skinned primitive: bind-pose vertices, triangles, colours, four bone weights
    (indices into the skeleton), and morph targets (name → vertex offsets)."""

    name: str
    vertices_m: np.ndarray
    faces: np.ndarray
    colors_rgb: np.ndarray
    joints: np.ndarray
    weights: np.ndarray
    normals: np.ndarray | None = None
    targets: dict[str, np.ndarray] = field(default_factory=dict)
    target_normals: dict[str, np.ndarray] = field(default_factory=dict)
    edge_m: np.ndarray | None = None
    across_rgb: np.ndarray | None = None
    casts_shadow: bool = True
    main_joints: np.ndarray | None = None


@dataclass(frozen=True, eq=False)
class ImportedAvatar:
    """A humanoid avatar read from glTF: skeleton (names, parents), bind pose, meshes,
    and from VRM its humanoid bones (VRM name → joint name), expressions and meta."""

    name: str
    joint_names: tuple[str, ...]
    parents: np.ndarray
    bind: Pose
    meshes: tuple[ImportedMesh, ...]
    humanoid: dict[str, str] = field(default_factory=dict)
    meta: dict = field(default_factory=dict)
    bones: dict[str, str] = field(default_factory=dict)  # a researcher's own mapping

    @property
    def morph_names(self) -> tuple[str, ...]:
        """Return every morph target's name, in order of first appearance."""
        return tuple(dict.fromkeys(n for mesh in self.meshes for n in mesh.targets))

    @property
    def height_m(self) -> float:
        """Return the skeleton's height at its bind pose."""
        return float(np.ptp(self.bind.positions_m[0][:, 1]))


def _skin_order(reader: Reader, joints: list[int]) -> tuple[list[int], np.ndarray]:
    """Return the skin's joints parents first and each one's parent (index, −1 for roots)."""
    nearest = reader.nearest_ancestors(set(joints))

    def parent_of(node: int) -> int | None:
        return nearest[node]

    children: dict[int | None, list[int]] = {}
    for node in joints:
        children.setdefault(parent_of(node), []).append(node)
    order, frontier = [], list(children.get(None, []))
    while frontier:
        node = frontier.pop(0)
        order.append(node)
        frontier.extend(children.get(node, []))
    position = {node: i for i, node in enumerate(order)}
    parents = np.array([position.get(parent_of(node), -1) for node in order], dtype=np.intp)
    return order, parents


def _bind_pose(reader: Reader, skin, order: list[int], turn: np.ndarray) -> Pose:
    """Return the joints' bind-pose global transforms from the inverse bind matrices."""
    count = len(skin.joints)
    if skin.inverseBindMatrices is None:
        inverse = np.repeat(np.eye(4)[None], count, axis=0)
    else:
        inverse = reader.read(skin.inverseBindMatrices).reshape(count, 4, 4).transpose(0, 2, 1)
    try:
        bind = np.linalg.inv(inverse)
    except np.linalg.LinAlgError:
        raise GltfError("The skin's inverse bind matrices cannot be inverted.") from None
    index = {node: k for k, node in enumerate(skin.joints)}
    bind = turn @ bind[[index[node] for node in order]]
    linear = bind[:, :3, :3]
    u, _, vt = np.linalg.svd(linear)  # the nearest rotation: the bind's scale dropped
    rotations = u @ vt
    rotations[np.linalg.det(rotations) < 0] *= -1
    quaternions = Rotation.from_matrix(rotations).as_quat()
    return Pose(quaternions=quaternions[None], positions_m=bind[None, :, :3, 3])


def _texture_colors(reader: Reader, material, uv: np.ndarray | None) -> np.ndarray | None:
    """Return the base colour texture sampled at *uv* (n, 3), or None without one."""
    info = material.pbrMetallicRoughness.baseColorTexture if material.pbrMetallicRoughness else None
    if info is None or uv is None:
        return None
    try:
        image = reader.gltf.images[reader.gltf.textures[info.index].source]
        view = reader.gltf.bufferViews[image.bufferView]
        blob = reader.buffers[view.buffer][
            view.byteOffset or 0 : (view.byteOffset or 0) + view.byteLength
        ]
        from PIL import Image

        with Image.open(io.BytesIO(blob)) as opened:
            pixels = np.asarray(opened.convert("RGB"), dtype=float) / 255.0
    except Exception:  # an external or broken image: the material's colour stands in
        return None
    height, width = pixels.shape[:2]
    u = np.mod(uv[:, 0], 1.0) * (width - 1)
    v = np.mod(uv[:, 1], 1.0) * (height - 1)
    srgb = pixels[v.round().astype(int), u.round().astype(int)]
    return srgb


def _colors(reader: Reader, primitive, count: int) -> np.ndarray:
    """Return a primitive's vertex colours (n, 3), sRGB 0–1 as the engine keeps them.

    glTF's COLOR_0 and baseColorFactor are linear, its colour textures sRGB-encoded
    (glTF 2.0 §3.7.2.1, §3.9.2): the product is formed in linear values, then encoded.
    """
    gltf = reader.gltf
    material = gltf.materials[primitive.material] if primitive.material is not None else None
    factor = np.ones(3)
    if material is not None and material.pbrMetallicRoughness is not None:
        factor = np.asarray(material.pbrMetallicRoughness.baseColorFactor or (1, 1, 1, 1))[:3]
    attributes = primitive.attributes
    if attributes.COLOR_0 is not None:
        return linear_to_srgb(reader.read(attributes.COLOR_0)[:, :3] * factor)
    uv = reader.read(attributes.TEXCOORD_0) if attributes.TEXCOORD_0 is not None else None
    sampled = _texture_colors(reader, material, uv) if material is not None else None
    if sampled is not None:
        return linear_to_srgb(srgb_to_linear(sampled) * factor)
    return np.broadcast_to(linear_to_srgb(factor), (count, 3)).copy()


def _weights(reader: Reader, attributes, count: int, skin_to_order: np.ndarray):
    """Return each vertex's four strongest bones (skeleton indices) and weights."""
    sets = [
        (getattr(attributes, f"JOINTS_{k}", None), getattr(attributes, f"WEIGHTS_{k}", None))
        for k in range(4)
    ]
    sets = [(j, w) for j, w in sets if j is not None and w is not None]
    if not sets:
        raise GltfError("A skinned mesh has no JOINTS_0 / WEIGHTS_0: no skin weights.")
    joints = np.concatenate([reader.read(j) for j, _ in sets], axis=1).astype(np.intp)
    weights = np.concatenate([reader.read(w) for _, w in sets], axis=1)
    if joints.max(initial=0) >= len(skin_to_order) or len(joints) != count:
        raise GltfError("A skinned mesh names joints its skin does not have.")
    top = np.argsort(-weights, axis=1)[:, :4]
    weights = np.take_along_axis(weights, top, axis=1)
    joints = skin_to_order[np.take_along_axis(joints, top, axis=1)]
    total = weights.sum(axis=1, keepdims=True)
    if (total <= 0).any():
        raise GltfError("A skinned mesh has vertices with no bone weight.")
    return joints, weights / total


def _faces(reader: Reader, primitive, count: int, name) -> np.ndarray:
    """Return a triangle primitive's faces (n, 3), checked against its *count* vertices."""
    faces = (
        reader.read(primitive.indices).astype(np.intp).reshape(-1, 3)
        if primitive.indices is not None
        else np.arange(count).reshape(-1, 3)
    )
    if faces.size and faces.max() >= count:
        raise GltfError(f"Mesh {name} has triangles naming missing vertices.")
    return faces


def _mesh(
    reader: Reader, node: int, primitive, number: int, skin_to_order: np.ndarray, turn: np.ndarray
) -> ImportedMesh:
    """Read one triangle primitive of a skinned mesh node."""
    gltf = reader.gltf
    mesh = gltf.meshes[gltf.nodes[node].mesh]
    attributes = primitive.attributes
    if attributes.POSITION is None:
        raise GltfError(f"Mesh {mesh.name or node} has a primitive without positions.")
    positions = reader.read(attributes.POSITION)
    count = len(positions)
    faces = _faces(reader, primitive, count, mesh.name or node)
    normals = reader.read(attributes.NORMAL) if attributes.NORMAL is not None else None
    joints, weights = _weights(reader, attributes, count, skin_to_order)
    names = (mesh.extras or {}).get("targetNames") or []
    targets, target_normals = {}, {}
    for k, target in enumerate(primitive.targets or []):
        name = str(names[k]) if k < len(names) else f"target_{k}"
        if "POSITION" in target:
            targets[name] = reader.read(target["POSITION"]) @ turn[:3, :3].T
        if "NORMAL" in target:
            target_normals[name] = reader.read(target["NORMAL"]) @ turn[:3, :3].T
    turned = positions @ turn[:3, :3].T
    colors, edge, across = _colors(reader, primitive, count), None, None
    extra = [getattr(attributes, name, None) for name in (EDGE, COLOR_INSIDE, COLOR_ACROSS)]
    if all(index is not None for index in extra):  # the engine's own colour edge
        edge, colors, across = (reader.read(index) for index in extra)
        edge = edge[:, 0]
    main = getattr(attributes, MAIN_JOINT, None)
    if main is not None:
        main = reader.read(main)[:, 0].round().astype(np.intp)
        usable = len(main) == count and main.min() >= 0 and main.max() < len(skin_to_order)
        main = skin_to_order[main] if usable else None
    ours = (mesh.extras or {}).get("signstudy") or {}
    return ImportedMesh(
        name=(mesh.name or "mesh") + (f".{number}" if number else ""),
        vertices_m=turned,
        faces=faces,
        colors_rgb=colors,
        joints=joints,
        weights=weights,
        normals=None if normals is None else normals @ turn[:3, :3].T,
        targets=targets,
        target_normals=target_normals,
        edge_m=edge,
        across_rgb=across,
        casts_shadow=bool(ours.get("casts_shadow", True)),
        main_joints=main,
    )


def read_gltf_avatar(data: bytes, source: str = "the file") -> ImportedAvatar:
    """Return the humanoid avatar of a GLB, ``.gltf`` (embedded buffers) or VRM file.

    Raise GltfError naming the problem: not glTF 2.0, truncated, no skin (no skeleton
    or weights), no triangles, a unit other than metres.
    """
    try:
        return _read_avatar(data, source)
    except GltfError:
        raise
    except DAMAGE as error:
        raise damaged(source, "avatar", error) from None


def _read_avatar(data: bytes, source: str) -> ImportedAvatar:
    gltf, buffers = load(data, source)
    reader = Reader(gltf, buffers, source)
    if not gltf.skins:
        raise GltfError(
            f"{source} has no skin: an avatar needs a skeleton with skin weights "
            "(export the armature and its vertex groups)."
        )
    skinned = [i for i, n in enumerate(gltf.nodes) if n.mesh is not None and n.skin is not None]
    if not skinned:
        raise GltfError(f"{source} has a skin but no mesh uses it.")
    skin_index = max(
        set(gltf.nodes[i].skin for i in skinned),
        key=lambda s: sum(gltf.nodes[i].skin == s for i in skinned),
    )
    skin = gltf.skins[skin_index]
    humanoid_nodes, meta, faces_back = vrm_humanoid(gltf)
    turn = np.diag([-1.0, 1.0, -1.0, 1.0]) if faces_back else np.eye(4)
    order, parents = _skin_order(reader, list(skin.joints))
    position = {node: k for k, node in enumerate(order)}
    skin_to_order = np.array([position[node] for node in skin.joints], dtype=np.intp)
    bind = _bind_pose(reader, skin, order, turn)
    names = []
    for k, node in enumerate(order):
        name = gltf.nodes[node].name or f"joint_{k}"
        names.append(name if name not in names else f"{name}_{k}")
    meshes, nodes_of = [], []
    for node in skinned:
        if gltf.nodes[node].skin != skin_index:
            continue
        read: dict[object, int] = {}  # the engine's edged part: its vertices, read once
        for number, primitive in enumerate(gltf.meshes[gltf.nodes[node].mesh].primitives):
            if (primitive.mode if primitive.mode is not None else TRIANGLES) != TRIANGLES:
                continue
            # The engine writes an edged part as primitives over one vertex set (one drawn
            # by the edge palette, one by vertex colours): one part again.
            same = getattr(primitive.attributes, EDGE, None) is not None
            key = primitive.attributes.POSITION if same else ("primitive", number)
            if key in read:
                first = meshes[read[key]]
                more = _faces(reader, primitive, len(first.vertices_m), first.name)
                meshes[read[key]] = replace(first, faces=np.concatenate([first.faces, more]))
                continue
            read[key] = len(meshes)
            meshes.append(_mesh(reader, node, primitive, number, skin_to_order, turn))
            nodes_of.append(node)
    if not meshes:
        raise GltfError(f"{source}'s skinned meshes have no triangles.")
    meshes = with_expressions(gltf, meshes, nodes_of)
    scene_name = gltf.scenes[0].name if gltf.scenes else None
    avatar = ImportedAvatar(
        name=str(meta.get("name") or meta.get("title") or scene_name or "avatar"),
        joint_names=tuple(names),
        parents=parents,
        bind=bind,
        meshes=tuple(meshes),
        humanoid={
            bone: names[position[node]]
            for bone, node in humanoid_nodes.items()
            if isinstance(node, int) and node in position
        },
        meta=meta,
        bones=_saved_bones(gltf),
    )
    _check_standing_humanoid(avatar, source)
    return avatar


# A humanoid has at least VRM's required bones: hips, spine, chest, neck, head, and
# each side's upper arm, lower arm, hand, upper leg, lower leg and foot.
MIN_HUMANOID_JOINTS = 15


def _check_standing_humanoid(avatar: ImportedAvatar, source: str) -> None:
    """Raise GltfError naming why *avatar* cannot be a signer: too few joints for a body,
    lying down, or not in metres."""
    low, high = HEIGHT_RANGE_M
    if low <= avatar.height_m <= high:
        return
    joints = avatar.joint_names
    if len(joints) < MIN_HUMANOID_JOINTS:
        shown = ", ".join(joints[:6]) + (" …" if len(joints) > 6 else "")
        raise GltfError(
            f"{source} is no humanoid: its skeleton has {len(joints)} joint(s) ({shown}); "
            f"a signer needs a body of at least {MIN_HUMANOID_JOINTS} (hips, spine, head, "
            "arms and hands)."
        )
    extent = float(np.ptp(avatar.bind.positions_m[0], axis=0).max())
    if low <= extent <= high:
        raise GltfError(
            f"{source}'s skeleton is {extent:.2f} m long but {avatar.height_m:.2f} m tall: "
            "it does not stand along +Y, glTF's up (export it standing, Y up)."
        )
    raise GltfError(
        f"{source}'s skeleton is {avatar.height_m:.2f} units tall: glTF is in "
        "metres (export with the scale applied)."
    )


def _saved_bones(gltf) -> dict[str, str]:
    """Return the bone mapping saved in the file (asset.extras.signstudy.bones)."""
    extras = (gltf.asset.extras or {}) if gltf.asset else {}
    ours = extras.get("signstudy") or {}
    bones, unmapped = ours.get("bones") or {}, ours.get("unmapped") or []
    if not isinstance(bones, dict) or not isinstance(unmapped, list):
        return {}
    return {**{str(k): str(v) for k, v in bones.items()}, **{str(k): "" for k in unmapped}}


def with_bone_mapping(data: bytes, bones: dict[str, str], source: str = "the file") -> bytes:
    """Return the GLB *data* with *bones* (joint name → engine joint, "" for none) saved
    in its ``asset.extras.signstudy`` (``bones``, and ``unmapped``: pygltflib drops
    empty strings), everything else as it was."""
    gltf, buffers = load(data, source)
    extras = dict(gltf.asset.extras or {})
    extras["signstudy"] = {
        **(extras.get("signstudy") or {}),
        "bones": {k: v for k, v in bones.items() if v},
        "unmapped": [k for k, v in bones.items() if not v],
    }
    gltf.asset.extras = extras
    if gltf.buffers and gltf.buffers[0].uri is None:
        gltf.set_binary_blob(buffers[0])
    return b"".join(gltf.save_to_bytes())
