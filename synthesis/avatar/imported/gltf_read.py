"""Read a glTF 2.0 file's data: accessors (strided, normalised, sparse), the node tree.

A GLB or a ``.gltf`` whose buffers are embedded (``data:`` URIs) is read whole in
memory through pygltflib; every accessor is checked to lie inside its buffer, so a
truncated file fails naming what is missing instead of reading past the end. Before
anything walks it, the file's structure is checked (:func:`check_structure`): indices
that name what exists, nodes that form trees (one parent each, no cycle), counts within
caps, so a hostile file is refused in time linear in its size (issue 51: a parent cycle
hung a web worker, an accessor claiming 10¹⁵ elements asked for petabytes).
"""

import base64
import json
import struct
from collections.abc import Mapping
from pathlib import Path
from urllib.parse import unquote

import numpy as np
import pygltflib as gl
from scipy.spatial.transform import Rotation

COMPONENTS = {
    5120: np.int8,
    5121: np.uint8,
    5122: np.int16,
    5123: np.uint16,
    5125: np.uint32,
    5126: np.float32,
}
WIDTHS = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4, "MAT2": 4, "MAT3": 9, "MAT4": 16}
MAX_FILE_BYTES = 512 * 1024**2
# Caps on what a file may declare: a VRM avatar has a few hundred nodes, a capture a
# few hundred thousand values per accessor.
MAX_NODES = 10_000
# Rows of any other top-level list (accessors, meshes, …): pygltflib spends ~0.2 ms on
# each object it builds, so these are counted in the raw JSON before it runs.
MAX_ROWS = 50_000
MAX_JSON_BYTES = 64 * 1024**2
MAX_ELEMENTS = 16 * 1024**2  # one accessor's values: count × components
SPARSE_INDICES = (5121, 5123, 5125)
# The engine's own vertex attributes in the GLBs it writes (glTF 2.0 §3.7.2.1: an
# application's names start with "_"): a colour edge through triangles, as drawn.
EDGE, COLOR_INSIDE, COLOR_ACROSS = "_SIGNSTUDY_EDGE_M", "_SIGNSTUDY_COLOR", "_SIGNSTUDY_ACROSS"
# ... and each vertex's main joint as the engine counts it (glTF lists a joint once).
MAIN_JOINT = "_SIGNSTUDY_MAIN_JOINT"


class GltfError(ValueError):
    """A glTF file that cannot be read as an avatar; the message names the problem."""


# What a reader may raise on a file whose parts disagree in ways no check above names
# (an accessor of the wrong length for its use, a matrix that cannot turn): the readers'
# entry points report them as a damaged file, never as a failure of their own.
DAMAGE = (ValueError, TypeError, KeyError, IndexError, AttributeError, ZeroDivisionError)


def damaged(source: str, what: str, error: Exception) -> GltfError:
    """Return the GltfError for a file in which reading *what* raised *error*."""
    return GltfError(f"{source} is damaged: its {what} cannot be read ({type(error).__name__}).")


def load(
    data: bytes, source: str = "the file", resources: Mapping[str, bytes] | None = None
) -> tuple[gl.GLTF2, list[bytes]]:
    """Return the parsed glTF of *data* (GLB or JSON) and its buffers' bytes.

    A ``.gltf`` may keep a buffer in a separate file: *resources* gives those files'
    bytes by the URI the document names (:func:`files_beside` reads them on the command
    line); an upload has none, so it must be one file.
    """
    if len(data) > MAX_FILE_BYTES:
        raise GltfError(f"{source} is larger than {MAX_FILE_BYTES // 1024**2} MB.")
    if data[:4] == b"glTF" and len(data) >= 12:
        declared = struct.unpack("<I", data[8:12])[0]
        if len(data) < declared:
            raise GltfError(
                f"{source} is truncated: it holds {len(data)} of the "
                f"{declared} bytes its header declares."
            )
    _check_counts(_json_document(data, source), source)
    try:
        if data[:4] == b"glTF":
            gltf = gl.GLTF2.load_from_bytes(data)
        else:
            gltf = gl.GLTF2.from_json(data.decode("utf-8"))
    except Exception as error:  # pygltflib raises many kinds on a broken file
        raise GltfError(f"{source} is not a readable glTF 2.0 file ({error}).") from None
    if not gltf.asset or not str(gltf.asset.version or "").startswith("2."):
        raise GltfError(
            f"{source} is not glTF 2.0 (asset.version {getattr(gltf.asset, 'version', None)!r})."
        )
    buffers = []
    for index, buffer in enumerate(gltf.buffers):
        if buffer.uri is None:
            blob = gltf.binary_blob() or b""
        elif buffer.uri.startswith("data:"):
            blob = base64.b64decode(buffer.uri.split(",", 1)[1])
        elif resources is not None and buffer.uri in resources:
            blob = resources[buffer.uri]
        else:
            raise GltfError(
                f"{source}: buffer {index} is the separate file {buffer.uri!r}; "
                "upload a GLB (one file) instead, or keep the file beside the .gltf on "
                "the command line."
            )
        if len(blob) < (buffer.byteLength or 0):
            raise GltfError(
                f"{source} is truncated: buffer {index} holds {len(blob)} of its "
                f"{buffer.byteLength} bytes."
            )
        buffers.append(blob)
    check_structure(gltf, buffers, source)
    return gltf, buffers


def files_beside(path: Path, data: bytes) -> dict[str, bytes]:
    """Return the separate buffer files the ``.gltf`` *data* at *path* names, read from
    its folder, by URI: only plain file names there (no folder, no ``..``), and at most
    :data:`MAX_FILE_BYTES` in all; GltfError names one that is not."""
    document = _json_document(data, path.name)
    _check_counts(document, path.name)
    found, total = {}, len(data)
    for buffer in document.get("buffers") or []:
        uri = buffer.get("uri") if isinstance(buffer, dict) else None
        if not isinstance(uri, str) or uri.startswith("data:"):
            continue
        name = unquote(uri)
        beside = path.parent / name
        if Path(name).name != name or name in (".", "..") or not beside.is_file():
            raise GltfError(
                f"{path.name}: buffer file {uri!r} is not a file beside it (a .gltf may name "
                "only files in its own folder)."
            )
        total += beside.stat().st_size
        if total > MAX_FILE_BYTES:
            raise GltfError(
                f"{path.name} and its buffers are larger than {MAX_FILE_BYTES // 1024**2} MB."
            )
        found[uri] = beside.read_bytes()
    return found


def _json_document(data: bytes, source: str):
    """Return the JSON document of GLB or ``.gltf`` *data*, parsed by the json module."""
    text = data
    if data[:4] == b"glTF":
        if len(data) < 20 or struct.unpack("<I", data[16:20])[0] != 0x4E4F534A:
            raise GltfError(f"{source} is not a readable glTF 2.0 file (no JSON chunk).")
        text = data[20 : 20 + struct.unpack("<I", data[12:16])[0]]
    if len(text) > MAX_JSON_BYTES:
        raise GltfError(f"{source}'s JSON is larger than {MAX_JSON_BYTES // 1024**2} MB.")
    try:
        return json.loads(text)
    except (ValueError, RecursionError):
        raise GltfError(f"{source} is not a readable glTF 2.0 file (its JSON).") from None


def _check_counts(document, source: str) -> None:
    """Raise GltfError if the raw JSON *document* holds more rows than are read."""
    if not isinstance(document, dict):
        raise GltfError(f"{source} is not a readable glTF 2.0 file (its JSON is no object).")
    nodes = document.get("nodes")
    if isinstance(nodes, list) and len(nodes) > MAX_NODES:
        raise GltfError(
            f"{source} has {len(nodes)} nodes, over the {MAX_NODES} an avatar or a motion may have."
        )
    for name, rows in document.items():
        if isinstance(rows, list) and len(rows) > MAX_ROWS:
            raise GltfError(f"{source} has {len(rows)} {name}, over the {MAX_ROWS} read.")


def _is_index(value, size: int) -> bool:
    return isinstance(value, int) and not isinstance(value, bool) and 0 <= value < size


def _is_count(value, limit: int) -> bool:
    return isinstance(value, int) and not isinstance(value, bool) and 0 <= value <= limit


def _node_tree(gltf: gl.GLTF2, source: str) -> dict[int, int]:
    """Return each node's parent; GltfError for a child that is no node, a node with two
    parents, or a cycle (glTF 2.0 §3.5.3: the nodes form disjoint trees)."""
    nodes = gltf.nodes or []
    if len(nodes) > MAX_NODES:
        raise GltfError(
            f"{source} has {len(nodes)} nodes, over the {MAX_NODES} an avatar or a motion may have."
        )
    parent: dict[int, int] = {}
    for index, node in enumerate(nodes):
        children = node.children or []
        if not isinstance(children, list):
            raise GltfError(f"{source}: node {index}'s children are not a list.")
        for child in children:
            if not _is_index(child, len(nodes)):
                raise GltfError(f"{source}: node {index} has a child that is not a node.")
            if child in parent or child == index:
                raise GltfError(f"{source}: node {child} has two parents; glTF's nodes form trees.")
            parent[child] = index
    done: set[int] = set()
    for start in range(len(nodes)):
        chain, seen, node = [], set(), start
        while node is not None and node not in done:
            if node in seen:
                raise GltfError(
                    f"{source}: node {node} is its own ancestor (a cycle in the node tree)."
                )
            seen.add(node)
            chain.append(node)
            node = parent.get(node)
        done.update(chain)
    return parent


def _check_accessor(gltf: gl.GLTF2, index: int, accessor, source: str) -> None:
    where = f"{source}: accessor {index}"
    if accessor.componentType not in COMPONENTS or accessor.type not in WIDTHS:
        raise GltfError(f"{where} has an unknown type.")
    if not _is_count(accessor.count, MAX_ELEMENTS // WIDTHS[accessor.type]):
        raise GltfError(
            f"{where} claims {accessor.count!r} elements; at most "
            f"{MAX_ELEMENTS // WIDTHS[accessor.type]} are read."
        )
    views = len(gltf.bufferViews or [])
    if accessor.bufferView is not None and not _is_index(accessor.bufferView, views):
        raise GltfError(f"{where} names a buffer view that does not exist.")
    sparse = accessor.sparse
    if sparse is None:
        return
    if not _is_count(sparse.count, accessor.count):
        raise GltfError(f"{where}'s sparse count exceeds its own count.")
    if sparse.indices is None or sparse.values is None:
        raise GltfError(f"{where}'s sparse part has no indices or values.")
    if sparse.indices.componentType not in SPARSE_INDICES:
        raise GltfError(f"{where}'s sparse indices have an unknown type.")
    for part in (sparse.indices, sparse.values):
        if not _is_index(part.bufferView, views):
            raise GltfError(f"{where}'s sparse part names a buffer view that does not exist.")


def _check_views(gltf: gl.GLTF2, buffers: list[bytes], source: str) -> None:
    for index, view in enumerate(gltf.bufferViews or []):
        length, offset = view.byteLength, view.byteOffset or 0
        if not _is_index(view.buffer, len(buffers)) or not _is_count(length, MAX_FILE_BYTES):
            raise GltfError(f"{source}: buffer view {index} names no buffer or no length.")
        if not _is_count(offset, MAX_FILE_BYTES) or offset + length > len(buffers[view.buffer]):
            raise GltfError(
                f"{source} is truncated or damaged: buffer view {index} ends past its buffer."
            )


def _check_nodes_and_skins(gltf: gl.GLTF2, source: str) -> None:
    nodes, accessors = len(gltf.nodes or []), len(gltf.accessors or [])
    for index, node in enumerate(gltf.nodes or []):
        if node.mesh is not None and not _is_index(node.mesh, len(gltf.meshes or [])):
            raise GltfError(f"{source}: node {index} names a mesh that does not exist.")
        if node.skin is not None and not _is_index(node.skin, len(gltf.skins or [])):
            raise GltfError(f"{source}: node {index} names a skin that does not exist.")
    for index, skin in enumerate(gltf.skins or []):
        joints = skin.joints if isinstance(skin.joints, list) else []
        valid = all(_is_index(joint, nodes) for joint in joints)
        if not joints or not valid or len(set(joints)) != len(joints):
            raise GltfError(f"{source}: skin {index}'s joints are not a list of distinct nodes.")
        matrices = skin.inverseBindMatrices
        if matrices is not None and not _is_index(matrices, accessors):
            raise GltfError(f"{source}: skin {index} names an accessor that does not exist.")


def _check_animations(gltf: gl.GLTF2, source: str) -> None:
    nodes, accessors = len(gltf.nodes or []), len(gltf.accessors or [])
    for index, animation in enumerate(gltf.animations or []):
        samplers = animation.samplers or []
        for sampler in samplers:
            if not (_is_index(sampler.input, accessors) and _is_index(sampler.output, accessors)):
                raise GltfError(
                    f"{source}: animation {index} names an accessor that does not exist."
                )
        for channel in animation.channels or []:
            target = channel.target
            node = target.node if target is not None else None
            if (
                not _is_index(channel.sampler, len(samplers))
                or target is None
                or (node is not None and not _is_index(node, nodes))
            ):
                raise GltfError(
                    f"{source}: animation {index} has a channel naming no sampler or node."
                )


def check_structure(gltf: gl.GLTF2, buffers: list[bytes], source: str = "the file") -> None:
    """Raise GltfError unless every index in the file names what exists, the nodes form
    trees, and every count is within its cap (checked before anything walks the file)."""
    _check_views(gltf, buffers, source)
    for index, accessor in enumerate(gltf.accessors or []):
        _check_accessor(gltf, index, accessor, source)
    _node_tree(gltf, source)
    _check_nodes_and_skins(gltf, source)
    _check_animations(gltf, source)


class Reader:
    """Read accessors and node transforms of one loaded glTF."""

    def __init__(self, gltf: gl.GLTF2, buffers: list[bytes], source: str = "the file"):
        self.gltf, self.buffers, self.source = gltf, buffers, source
        self.parent = _node_tree(gltf, source)  # checked: one parent each, no cycle

    def nearest_ancestors(self, members: set[int]) -> dict[int, int | None]:
        """Return each node's nearest proper ancestor among *members* (None: none), in
        time linear in the node count (each path up is walked once)."""
        found: dict[int, int | None] = {}
        for start in range(len(self.gltf.nodes or [])):
            path, node = [], start
            while node not in found:
                path.append(node)
                up = self.parent.get(node)
                if up is None or up in members:
                    found[node] = up
                    path.pop()
                    break
                node = up
            for below in reversed(path):
                found[below] = found[self.parent[below]]
        return found

    def _view(self, view: int, offset: int, dtype, width: int, count: int) -> np.ndarray:
        try:
            bv = self.gltf.bufferViews[view]
            blob = self.buffers[bv.buffer]
        except (IndexError, TypeError):
            raise GltfError(f"{self.source}: buffer view {view} does not exist.") from None
        item = np.dtype(dtype).itemsize * width
        stride = bv.byteStride or item
        start = (bv.byteOffset or 0) + offset
        needed = start + stride * (count - 1) + item if count else start
        if needed > min(len(blob), (bv.byteOffset or 0) + bv.byteLength):
            raise GltfError(
                f"{self.source} is truncated or damaged: buffer view {view} ends before its data."
            )
        raw = np.frombuffer(blob, np.uint8, needed - start, start)
        rows = np.lib.stride_tricks.as_strided(raw, (count, item), (stride, 1))
        return np.ascontiguousarray(rows).view(dtype).reshape(count, width)

    def read(self, index: int) -> np.ndarray:
        """Return accessor *index* as floats (count, width), normalised integers scaled."""
        try:
            accessor = self.gltf.accessors[index]
        except (IndexError, TypeError):
            raise GltfError(f"{self.source}: accessor {index} does not exist.") from None
        dtype, width = COMPONENTS.get(accessor.componentType), WIDTHS.get(accessor.type)
        if dtype is None or width is None:
            raise GltfError(f"{self.source}: accessor {index} has an unknown type.")
        if accessor.bufferView is None:
            values = np.zeros((accessor.count, width))
        else:
            values = self._view(
                accessor.bufferView, accessor.byteOffset or 0, dtype, width, accessor.count
            ).astype(float)
        if accessor.sparse is not None and accessor.sparse.count:
            sparse = accessor.sparse
            rows = self._view(
                sparse.indices.bufferView,
                sparse.indices.byteOffset or 0,
                COMPONENTS[sparse.indices.componentType],
                1,
                sparse.count,
            )[:, 0]
            if rows.size and rows.max() >= len(values):
                raise GltfError(
                    f"{self.source}: accessor {index}'s sparse indices name elements it "
                    "does not have."
                )
            values[rows.astype(np.intp)] = self._view(
                sparse.values.bufferView, sparse.values.byteOffset or 0, dtype, width, sparse.count
            )
        if accessor.normalized and np.issubdtype(dtype, np.integer):
            values = values / float(np.iinfo(dtype).max)
        return values

    def local_matrix(self, node: int) -> np.ndarray:
        """Return a node's transform relative to its parent (4, 4)."""
        n = self.gltf.nodes[node]
        if n.matrix is not None and len(n.matrix) == 16:
            return np.asarray(n.matrix, float).reshape(4, 4).T  # column-major
        matrix = np.eye(4)
        scale = np.asarray(n.scale if n.scale is not None else (1, 1, 1), float)
        rotation = Rotation.from_quat(n.rotation if n.rotation is not None else (0, 0, 0, 1))
        matrix[:3, :3] = rotation.as_matrix() * scale
        matrix[:3, 3] = n.translation if n.translation is not None else (0, 0, 0)
        return matrix

    def world_matrix(self, node: int) -> np.ndarray:
        """Return a node's transform in the scene (4, 4)."""
        matrix = self.local_matrix(node)
        while node in self.parent:
            node = self.parent[node]
            matrix = self.local_matrix(node) @ matrix
        return matrix
