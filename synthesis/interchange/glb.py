"""Write a clip as glTF 2.0 binary (GLB): the skinned avatar, its motion and the camera.

What Blender, Unity or three.js open is what the renderer drew: each skinned part is a
mesh with the engine's bind-pose vertices, normals, colours (a palette texture where the
part has a colour edge) and four bone weights a vertex; its joints are nodes whose
inverse bind matrices are the engine's ``B⁻¹``; the animation keys every joint's local
rotation and translation at every frame (linear interpolation, so a player between
frames blends as the engine would resample); the face's blendshapes are morph targets
(sparse: only the vertices they move) whose weights are keyed per frame. glTF shares the
engine's frame (metres, +Y up, the signer facing +Z) and its scalar-last quaternions, so
nothing is converted. Skinned that way (glTF 2.0 §3.7.3), a frame's vertices are the
engine's to float32 precision (tests/synthesis/test_glb.py). The camera that filmed the
clip is a camera node, keyed per frame when it follows the hand.
"""

import numpy as np
import pygltflib as gl
from scipy.spatial.transform import Rotation

from synthesis.avatar.colour import srgb_to_linear
from synthesis.avatar.imported.gltf_read import COLOR_ACROSS, COLOR_INSIDE, EDGE, MAIN_JOINT
from synthesis.interchange.edge_texture import EdgeTexture, edge_texture
from synthesis.render.scene import CameraPath, CameraPreset, look_at
from synthesis.skeleton.kinematics import Pose, local_transforms
from synthesis.skeleton.rotations import quat_to_matrix

FLOAT, UINT16, UINT32 = gl.FLOAT, gl.UNSIGNED_SHORT, gl.UNSIGNED_INT
_TYPES = {1: gl.SCALAR, 2: gl.VEC2, 3: gl.VEC3, 4: gl.VEC4, 16: gl.MAT4}
_DTYPES = {FLOAT: np.float32, UINT16: np.uint16, UINT32: np.uint32}


def continuous(quaternions: np.ndarray) -> np.ndarray:
    """Return keyed quaternions (n_frames, …, 4) each in the hemisphere of the frame
    before, so that interpolating between keys never takes the long way round."""
    flip = np.sum(quaternions[1:] * quaternions[:-1], axis=-1) < 0
    signs = np.cumprod(np.where(flip, -1.0, 1.0), axis=0)
    out = quaternions.copy()
    out[1:] *= signs[..., None]
    return out


def inverse_bind_matrices(bind: Pose) -> np.ndarray:
    """Return the inverse of each joint's bind-pose global transform, (n, 4, 4)."""
    rotations = quat_to_matrix(np.asarray(bind.quaternions, float)[0])
    positions = np.asarray(bind.positions_m, float)[0]
    inverse = np.zeros((len(positions), 4, 4))
    inverse[:, :3, :3] = np.swapaxes(rotations, -1, -2)
    inverse[:, :3, 3] = -np.einsum("nij,nj->ni", inverse[:, :3, :3], positions)
    inverse[:, 3, 3] = 1.0
    return inverse


class BufferBuilder:
    """The GLB's one binary buffer, its views and accessors, built as data is added."""

    def __init__(self, gltf: gl.GLTF2):
        self.gltf, self.chunks, self.length = gltf, [], 0

    def add(
        self, data: np.ndarray, component: int, target: int | None = None, bounds: bool = False
    ) -> int:
        """Add *data* (count, width) as an accessor; return its index."""
        data = np.ascontiguousarray(data, dtype=_DTYPES[component])
        data = data.reshape(len(data), -1)
        view = self._view(data.tobytes(), target)
        accessor = gl.Accessor(
            bufferView=view, componentType=component, count=len(data), type=_TYPES[data.shape[1]]
        )
        if bounds:
            accessor.min = data.min(axis=0).astype(float).tolist()
            accessor.max = data.max(axis=0).astype(float).tolist()
        self.gltf.accessors.append(accessor)
        return len(self.gltf.accessors) - 1

    def add_sparse(self, count: int, rows: np.ndarray, values: np.ndarray) -> int:
        """Add a VEC3 float accessor of *count* zeros but *values* at *rows*."""
        rows = np.ascontiguousarray(rows, dtype=np.uint32)
        values = np.ascontiguousarray(values, dtype=np.float32)
        sparse = gl.Sparse(
            count=len(rows),
            indices=gl.AccessorSparseIndices(
                bufferView=self._view(rows.tobytes()), componentType=UINT32
            ),
            values=gl.AccessorSparseValues(bufferView=self._view(values.tobytes())),
        )
        accessor = gl.Accessor(
            componentType=FLOAT,
            count=count,
            type=gl.VEC3,
            sparse=sparse,
            min=values.min(axis=0).astype(float).tolist(),
            max=values.max(axis=0).astype(float).tolist(),
        )
        accessor.byteOffset = None  # no buffer view: all zeros but the sparse values
        # Bounds of a morph target include the zeros of the vertices it leaves alone.
        accessor.min = np.minimum(accessor.min, 0.0).tolist()
        accessor.max = np.maximum(accessor.max, 0.0).tolist()
        self.gltf.accessors.append(accessor)
        return len(self.gltf.accessors) - 1

    def add_bytes(self, data: bytes) -> int:
        """Add raw bytes (an image) as a buffer view; return its index."""
        return self._view(data)

    def _view(self, data: bytes, target: int | None = None) -> int:
        padding = (-self.length) % 4
        if padding:
            self.chunks.append(b"\x00" * padding)
            self.length += padding
        view = gl.BufferView(buffer=0, byteOffset=self.length, byteLength=len(data))
        if target is not None:
            view.target = target
        self.gltf.bufferViews.append(view)
        self.chunks.append(data)
        self.length += len(data)
        return len(self.gltf.bufferViews) - 1

    def finish(self) -> bytes:
        data = b"".join(self.chunks)
        self.gltf.buffers = [gl.Buffer(byteLength=len(data))]
        return data


def _joint_nodes(gltf: gl.GLTF2, skeleton, bind_q: np.ndarray, bind_t: np.ndarray) -> list[int]:
    """Add a node per joint at its bind-pose local transform; return the root nodes."""
    parents = skeleton.parents
    first = len(gltf.nodes)
    bind_q = bind_q / np.linalg.norm(bind_q, axis=-1, keepdims=True)
    for index, joint in enumerate(skeleton.joints):
        gltf.nodes.append(
            gl.Node(
                name=joint.name,
                rotation=np.clip(bind_q[index], -1, 1).tolist(),
                translation=bind_t[index].tolist(),
            )
        )
    for index, parent in enumerate(parents):
        if parent >= 0:
            gltf.nodes[first + parent].children.append(first + index)
    return [first + index for index, parent in enumerate(parents) if parent < 0]


def distinct_weights(skin, n_joints: int) -> tuple[np.ndarray, np.ndarray]:
    """Return a skin's bones and weights (n, 4) with each bone once a vertex and joint 0
    in the unused slots, as glTF requires (§3.7.3.1); the engine lets a rigid part list
    its one bone in every slot."""
    matrix = skin.matrix(n_joints).tocsr()
    matrix.sum_duplicates()
    # The engine's sums leave rounding dust (−2.2e-16): no weight, where glTF's are
    # non-negative and sum to one (§3.7.3.1; the Khronos validator refused it).
    matrix.data[matrix.data < 0] = 0.0
    matrix.eliminate_zeros()
    counts = np.diff(matrix.indptr)
    rows = np.repeat(np.arange(len(counts)), counts)
    slots = np.arange(len(rows)) - np.repeat(matrix.indptr[:-1], counts)
    joints = np.zeros((len(counts), 4), dtype=np.intp)
    weights = np.zeros((len(counts), 4))
    joints[rows, slots], weights[rows, slots] = matrix.indices, matrix.data
    return joints, weights / weights.sum(axis=1, keepdims=True)


def _edge_material(gltf: gl.GLTF2, buffer: BufferBuilder, texture: EdgeTexture) -> int:
    """Add a material coloured by *texture*, sampled NEAREST (the edge stays sharp)."""
    import imageio.v3 as iio

    png = iio.imwrite("<bytes>", texture.image_srgb, extension=".png")
    gltf.images.append(gl.Image(bufferView=buffer.add_bytes(png), mimeType="image/png"))
    gltf.samplers.append(
        gl.Sampler(
            magFilter=gl.NEAREST,
            minFilter=gl.NEAREST,
            wrapS=gl.CLAMP_TO_EDGE,
            wrapT=gl.CLAMP_TO_EDGE,
        )
    )
    gltf.textures.append(gl.Texture(sampler=len(gltf.samplers) - 1, source=len(gltf.images) - 1))
    gltf.materials.append(
        gl.Material(
            name="clothes and face (edge palette)",
            doubleSided=False,
            pbrMetallicRoughness=gl.PbrMetallicRoughness(
                baseColorFactor=[1, 1, 1, 1],
                baseColorTexture=gl.TextureInfo(index=len(gltf.textures) - 1),
                metallicFactor=0.0,
                roughnessFactor=0.7,
            ),
        )
    )
    return len(gltf.materials) - 1


def _morph_targets(buffer: BufferBuilder, part) -> list[dict]:
    """Add a part's blendshapes as sparse morph targets; return them (none without)."""
    if part.morphs is None:
        return []
    count, rows = len(part.vertices_m), part.morphs.vertices
    return [
        {
            "POSITION": buffer.add_sparse(count, rows, part.morphs.offsets_m[k]),
            "NORMAL": buffer.add_sparse(count, rows, part.morphs.normal_offsets[k]),
        }
        for k in range(len(part.morphs.names))
    ]


def _part_mesh(gltf: gl.GLTF2, buffer: BufferBuilder, part, material: int, n_joints: int) -> int:
    """Add one skinned part as a mesh (its blendshapes as sparse targets); return it.

    A part with a colour edge is drawn by its edge palette texture
    (:mod:`synthesis.interchange.edge_texture`), which keeps the edge sharp where vertex
    colours would blur it across its triangles in every other tool. Its triangles whose
    corners have different colour pairs, which the engine blends, keep vertex colours
    in a second primitive over the same vertices.
    """
    joints, weights = distinct_weights(part.weights, n_joints)
    shared = {
        "POSITION": buffer.add(part.vertices_m, FLOAT, gl.ARRAY_BUFFER, bounds=True),
        "NORMAL": buffer.add(part.normals, FLOAT, gl.ARRAY_BUFFER),
        "JOINTS_0": buffer.add(joints, UINT16, gl.ARRAY_BUFFER),
        "WEIGHTS_0": buffer.add(weights, FLOAT, gl.ARRAY_BUFFER),
    }
    # The engine's own reader takes the edge back exactly from these (other tools ignore
    # them), and each vertex's main joint.
    if part.edge_m is not None:
        shared[EDGE] = buffer.add(part.edge_m.reshape(-1, 1), FLOAT, gl.ARRAY_BUFFER)
        shared[COLOR_INSIDE] = buffer.add(part.colors_rgb, FLOAT, gl.ARRAY_BUFFER)
        shared[COLOR_ACROSS] = buffer.add(part.across_rgb, FLOAT, gl.ARRAY_BUFFER)
    main_joints = part.weights.main_joints().reshape(-1, 1)
    shared[MAIN_JOINT] = buffer.add(main_joints, FLOAT, gl.ARRAY_BUFFER)
    faces = np.asarray(part.faces)
    edged = (
        None if part.edge_m is None else edge_texture(part.edge_m, part.colors_rgb, part.across_rgb)
    )

    def vertex_colours() -> dict:
        rgb = srgb_to_linear(part.vertex_rgb())
        return {"COLOR_0": buffer.add(rgb, FLOAT, gl.ARRAY_BUFFER)}

    if edged is None:
        drawn = [(faces, vertex_colours(), material)]  # (triangles, attributes, material)
    else:
        one_pair = (edged.rows[faces] == edged.rows[faces][:, :1]).all(axis=1)
        texcoords = {"TEXCOORD_0": buffer.add(edged.texcoords, FLOAT, gl.ARRAY_BUFFER)}
        drawn = [(faces[one_pair], texcoords, _edge_material(gltf, buffer, edged))]
        if not one_pair.all():
            drawn.append((faces[~one_pair], vertex_colours(), material))
    targets = _morph_targets(buffer, part)
    primitives = []
    for triangles, extra, used in drawn:
        attributes = gl.Attributes()
        for name, accessor in {**shared, **extra}.items():
            setattr(attributes, name, accessor)
        primitives.append(
            gl.Primitive(
                attributes=attributes,
                material=used,
                indices=buffer.add(triangles.reshape(-1, 1), UINT32, gl.ELEMENT_ARRAY_BUFFER),
                targets=list(targets),
            )
        )
    mesh = gl.Mesh(
        name=part.name,
        primitives=primitives,
        extras={"signstudy": {"casts_shadow": bool(part.casts_shadow)}},
    )
    if part.morphs is not None:
        mesh.weights = [0.0] * len(part.morphs.names)
        mesh.extras["targetNames"] = list(part.morphs.names)
    gltf.meshes.append(mesh)
    return len(gltf.meshes) - 1


def _camera_node(gltf: gl.GLTF2, camera, width: int, height: int) -> tuple[int, np.ndarray]:
    """Add the camera; return its node and its transforms (frames, 4, 4)."""
    gltf.cameras.append(
        gl.Camera(
            type="perspective",
            name=camera.name,
            perspective=gl.Perspective(
                yfov=float(np.radians(camera.yfov_deg)),
                aspectRatio=width / height,
                znear=0.01,
                zfar=100.0,
            ),
        )
    )
    if isinstance(camera, CameraPath):
        poses = np.stack(
            [look_at(e, t) for e, t in zip(camera.eye_m, camera.target_m, strict=True)]
        )
    else:
        poses = camera.pose()[None]
    node = gl.Node(
        name=camera.name,
        camera=len(gltf.cameras) - 1,
        translation=poses[0, :3, 3].tolist(),
        rotation=Rotation.from_matrix(poses[0, :3, :3]).as_quat().tolist(),
    )
    gltf.nodes.append(node)
    return len(gltf.nodes) - 1, poses


def _key(gltf, buffer, times: int, node: int, path: str, values: np.ndarray) -> None:
    animation = gltf.animations[0]
    animation.samplers.append(
        gl.AnimationSampler(input=times, interpolation="LINEAR", output=buffer.add(values, FLOAT))
    )
    animation.channels.append(
        gl.AnimationChannel(
            sampler=len(animation.samplers) - 1,
            target=gl.AnimationChannelTarget(node=node, path=path),
        )
    )


def avatar_glb(
    avatar,
    pose: Pose,
    rate_hz: float,
    morph_weights: np.ndarray | None = None,
    camera: CameraPreset | CameraPath | None = None,
    width: int = 640,
    height: int = 480,
    name: str = "clip",
    extras: dict | None = None,
) -> bytes:
    """Return a GLB of *avatar* moving through *pose* (global transforms, one per frame)
    at *rate_hz*, its blendshapes at *morph_weights* (frames, the drive's names), filmed
    by *camera*; *extras* (JSON data) is kept in the asset's extras, with the frame rate
    as ``signstudy.rate_hz`` (glTF keys times in seconds and names no rate; Blender
    places the keys at its scene's rate, 24 fps unless set: researcher guide).
    """
    skeleton = avatar.rig.skeleton
    parents = np.asarray(skeleton.parents)
    n_frames = len(pose.quaternions)
    gltf = gl.GLTF2(asset=gl.Asset(generator="SignStudy synthesis", version="2.0"))
    extras = dict(extras or {})
    extras["signstudy"] = {**extras.get("signstudy", {}), "rate_hz": float(rate_hz)}
    gltf.asset.extras = extras
    gltf.animations.append(gl.Animation(name=name))
    buffer = BufferBuilder(gltf)
    bind_q, bind_t = local_transforms(parents, avatar.bind_pose)
    roots = _joint_nodes(gltf, skeleton, bind_q[0], bind_t[0])
    joints = list(range(roots[0], roots[0] + len(skeleton.joints)))
    gltf.skins.append(
        gl.Skin(
            name=avatar.name,
            joints=joints,
            skeleton=roots[0],
            inverseBindMatrices=buffer.add(
                np.swapaxes(inverse_bind_matrices(avatar.bind_pose), 1, 2).reshape(len(joints), 16),
                FLOAT,
            ),
        )
    )
    gltf.materials.append(
        gl.Material(
            name="skin and clothes (vertex colours)",
            doubleSided=False,
            pbrMetallicRoughness=gl.PbrMetallicRoughness(
                baseColorFactor=[1, 1, 1, 1], metallicFactor=0.0, roughnessFactor=0.7
            ),
        )
    )
    names = () if avatar.drive is None else avatar.drive.names
    scene_nodes = list(roots)
    times = buffer.add(np.arange(n_frames, dtype=np.float64)[:, None] / rate_hz, FLOAT, bounds=True)
    for part in avatar.parts:
        mesh = _part_mesh(gltf, buffer, part, 0, len(joints))
        gltf.nodes.append(gl.Node(name=part.name, mesh=mesh, skin=0))
        scene_nodes.append(len(gltf.nodes) - 1)
        if part.morphs is not None and morph_weights is not None:
            columns = [names.index(n) for n in part.morphs.names]
            _key(
                gltf,
                buffer,
                times,
                scene_nodes[-1],
                "weights",
                np.asarray(morph_weights)[:, columns].reshape(-1, 1),
            )
    local_q, local_t = local_transforms(parents, pose)
    local_q = continuous(local_q)
    for index, node in enumerate(joints):
        _key(gltf, buffer, times, node, "rotation", local_q[:, index])
        _key(gltf, buffer, times, node, "translation", local_t[:, index])
    if camera is not None:
        node, poses = _camera_node(gltf, camera, width, height)
        scene_nodes.append(node)
        if len(poses) > 1:
            _key(gltf, buffer, times, node, "translation", poses[:, :3, 3])
            _key(
                gltf,
                buffer,
                times,
                node,
                "rotation",
                Rotation.from_matrix(poses[:, :3, :3]).as_quat(),
            )
    gltf.scenes.append(gl.Scene(name=name, nodes=scene_nodes))
    gltf.scene = 0
    gltf.set_binary_blob(buffer.finish())
    return b"".join(gltf.save_to_bytes())
