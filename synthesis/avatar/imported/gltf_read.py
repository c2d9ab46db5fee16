"""Read a glTF 2.0 file's data: accessors (strided, normalised, sparse), the node tree.

A GLB or a ``.gltf`` whose buffers are embedded (``data:`` URIs) is read whole in
memory through pygltflib; every accessor is checked to lie inside its buffer, so a
truncated file fails naming what is missing instead of reading past the end.
"""

import base64
import struct

import numpy as np
import pygltflib as gl
from scipy.spatial.transform import Rotation

COMPONENTS = {
    5120: np.int8, 5121: np.uint8, 5122: np.int16, 5123: np.uint16, 5125: np.uint32,
    5126: np.float32,
}  # fmt: skip
WIDTHS = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4, "MAT2": 4, "MAT3": 9, "MAT4": 16}
MAX_FILE_BYTES = 512 * 1024**2
# The engine's own vertex attributes in the GLBs it writes (glTF 2.0 §3.7.2.1: an
# application's names start with "_"): a colour edge through triangles, as drawn.
EDGE, COLOR_INSIDE, COLOR_ACROSS = "_SIGNSTUDY_EDGE_M", "_SIGNSTUDY_COLOR", "_SIGNSTUDY_ACROSS"
# ... and each vertex's main joint as the engine counts it (glTF lists a joint once).
MAIN_JOINT = "_SIGNSTUDY_MAIN_JOINT"


class GltfError(ValueError):
    """A glTF file that cannot be read as an avatar; the message names the problem."""


def load(data: bytes, source: str = "the file") -> tuple[gl.GLTF2, list[bytes]]:
    """Return the parsed glTF of *data* (GLB or JSON) and its buffers' bytes."""
    if len(data) > MAX_FILE_BYTES:
        raise GltfError(f"{source} is larger than {MAX_FILE_BYTES // 1024**2} MB.")
    if data[:4] == b"glTF" and len(data) >= 12:
        declared = struct.unpack("<I", data[8:12])[0]
        if len(data) < declared:
            raise GltfError(f"{source} is truncated: it holds {len(data)} of the "
                            f"{declared} bytes its header declares.")  # fmt: skip
    try:
        if data[:4] == b"glTF":
            gltf = gl.GLTF2.load_from_bytes(data)
        else:
            gltf = gl.GLTF2.from_json(data.decode("utf-8"))
    except Exception as error:  # pygltflib raises many kinds on a broken file
        raise GltfError(f"{source} is not a readable glTF 2.0 file ({error}).") from None
    if not gltf.asset or not str(gltf.asset.version or "").startswith("2."):
        raise GltfError(f"{source} is not glTF 2.0 (asset.version "
                        f"{getattr(gltf.asset, 'version', None)!r}).")  # fmt: skip
    buffers = []
    for index, buffer in enumerate(gltf.buffers):
        if buffer.uri is None:
            blob = gltf.binary_blob() or b""
        elif buffer.uri.startswith("data:"):
            blob = base64.b64decode(buffer.uri.split(",", 1)[1])
        else:
            raise GltfError(f"{source}: buffer {index} is the separate file {buffer.uri!r}; "
                            "upload a GLB (one file) instead.")  # fmt: skip
        if len(blob) < (buffer.byteLength or 0):
            raise GltfError(f"{source} is truncated: buffer {index} holds {len(blob)} of its "
                            f"{buffer.byteLength} bytes.")  # fmt: skip
        buffers.append(blob)
    return gltf, buffers


class Reader:
    """Read accessors and node transforms of one loaded glTF."""

    def __init__(self, gltf: gl.GLTF2, buffers: list[bytes], source: str = "the file"):
        self.gltf, self.buffers, self.source = gltf, buffers, source
        self.parent = {}
        for index, node in enumerate(gltf.nodes):
            for child in node.children or []:
                self.parent[child] = index

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
            raise GltfError(f"{self.source} is truncated or damaged: buffer view {view} "
                            "ends before its data.")  # fmt: skip
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
            values = self._view(accessor.bufferView, accessor.byteOffset or 0, dtype, width,
                                accessor.count).astype(float)  # fmt: skip
        if accessor.sparse is not None and accessor.sparse.count:
            sparse = accessor.sparse
            rows = self._view(
                sparse.indices.bufferView,
                sparse.indices.byteOffset or 0,
                COMPONENTS[sparse.indices.componentType],
                1,
                sparse.count,
            )[:, 0]
            values[rows.astype(np.intp)] = self._view(
                sparse.values.bufferView, sparse.values.byteOffset or 0, dtype, width,
                sparse.count)  # fmt: skip
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
