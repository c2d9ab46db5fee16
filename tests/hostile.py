"""Make hostile files from good ones: glTF/VRM, BVH, .pose, zips and manifests.

Each maker takes a good file's bytes and returns a damaged or crafted one, the way an
attacker edits a real file (issue 51's attack run: a parent cycle, a 200,000-node chain,
accessors claiming 10¹⁵ elements, animation keys to 10¹² s, VRM parts of the wrong JSON
type, sparse indices out of range). The named cases replay the issue's findings; the
Hypothesis strategies generate many more for the standing harness
(tests/studyplatform/test_hostile_inputs.py).
"""

import io
import json
import struct
import zipfile
from collections.abc import Callable

import numpy as np
from hypothesis import strategies as st

JSON_CHUNK, BIN_CHUNK = 0x4E4F534A, 0x004E4942


def glb_parts(data: bytes) -> tuple[dict, bytes]:
    """Return a GLB's JSON document and binary chunk."""
    length, kind = struct.unpack("<II", data[12:20])
    assert kind == JSON_CHUNK
    document = json.loads(data[20 : 20 + length])
    rest = data[20 + length :]
    blob = rest[8 : 8 + struct.unpack("<I", rest[:4])[0]] if len(rest) >= 8 else b""
    return document, blob


def glb_pack(document: dict, blob: bytes) -> bytes:
    """Return a GLB of *document* and *blob* (the buffer's length set to the blob's)."""
    if document.get("buffers"):
        document["buffers"][0]["byteLength"] = len(blob)
    text = json.dumps(document).encode()
    text += b" " * (-len(text) % 4)
    blob += b"\0" * (-len(blob) % 4)
    chunks = struct.pack("<II", len(text), JSON_CHUNK) + text
    if blob:
        chunks += struct.pack("<II", len(blob), BIN_CHUNK) + blob
    return struct.pack("<4sII", b"glTF", 2, 12 + len(chunks)) + chunks


def _append(document: dict, blob: bytes, values: np.ndarray, kind: str) -> tuple[bytes, int]:
    """Return *blob* with float32 *values* appended as a new accessor, and its index."""
    data = np.ascontiguousarray(values, np.float32).tobytes()
    offset = len(blob) + (-len(blob) % 4)
    blob = blob + b"\0" * (offset - len(blob)) + data
    document.setdefault("bufferViews", []).append(
        {"buffer": 0, "byteOffset": offset, "byteLength": len(data)}
    )
    view = len(document["bufferViews"]) - 1
    accessor = {"bufferView": view, "componentType": 5126, "count": len(values), "type": kind}
    document.setdefault("accessors", []).append(accessor)
    return blob, len(document["accessors"]) - 1


def with_animation(data: bytes, times: list[float], node: int = 1) -> bytes:
    """Return GLB *data* with an animation turning *node* at key *times*."""
    document, blob = glb_parts(data)
    blob, times_accessor = _append(document, blob, np.array(times)[:, None], "SCALAR")
    quaternions = np.tile([0.0, 0.0, 0.0, 1.0], (len(times), 1))
    blob, values_accessor = _append(document, blob, quaternions, "VEC4")
    channel = {"sampler": 0, "target": {"node": node, "path": "rotation"}}
    sampler = {"input": times_accessor, "output": values_accessor}
    document["animations"] = [{"channels": [channel], "samplers": [sampler]}]
    return glb_pack(document, blob)


def _edit(change: Callable[[dict], None]) -> Callable[[bytes], bytes]:
    def make(data: bytes) -> bytes:
        document, blob = glb_parts(data)
        change(document)
        return glb_pack(document, blob)

    return make


def _cycle(document: dict) -> None:
    document["nodes"][1].setdefault("children", []).append(0)  # 0 → … → 1 → 0


def _two_parents(document: dict) -> None:
    document["nodes"][2].setdefault("children", []).append(document["nodes"][0]["children"][0])


def _chain(count: int) -> Callable[[dict], None]:
    def change(document: dict) -> None:
        first = len(document["nodes"])
        document["nodes"] += [{"children": [first + k + 1]} for k in range(count - 1)]
        document["nodes"].append({"name": "end"})
        document["nodes"][0].setdefault("children", []).append(first)

    return change


def long_chain(data: bytes, count: int) -> bytes:
    """Return GLB *data* with a chain of *count* nodes hung below its first node (legal
    under the node cap: readers must still walk it in linear time)."""
    return _edit(_chain(count))(data)


def _huge_accessor(document: dict) -> None:
    document["accessors"].append({"componentType": 5126, "count": 10**15, "type": "VEC3"})
    document["skins"][0]["inverseBindMatrices"] = len(document["accessors"]) - 1


def _sparse_type(indices_type: int) -> Callable[[dict], None]:
    def change(document: dict) -> None:
        accessor = document["skins"][0]["inverseBindMatrices"]
        view = document["accessors"][accessor]["bufferView"]
        document["accessors"][accessor]["sparse"] = {
            "count": 1,
            "indices": {"bufferView": view, "componentType": indices_type},
            "values": {"bufferView": view},
        }

    return change


def _sparse_out_of_range(data: bytes) -> bytes:
    document, blob = glb_parts(data)
    accessor = document["skins"][0]["inverseBindMatrices"]
    offset = len(blob) + (-len(blob) % 4)
    blob = blob + b"\0" * (offset - len(blob)) + struct.pack("<I", 10**9)
    document["bufferViews"].append({"buffer": 0, "byteOffset": offset, "byteLength": 4})
    view = document["accessors"][accessor]["bufferView"]
    document["accessors"][accessor]["sparse"] = {
        "count": 1,
        "indices": {"bufferView": len(document["bufferViews"]) - 1, "componentType": 5125},
        "values": {"bufferView": view},
    }
    return glb_pack(document, blob)


def _vrm(change: Callable[[dict], None]) -> Callable[[dict], None]:
    def edit(document: dict) -> None:
        change(document["extensions"]["VRMC_vrm"])

    return edit


def _humanoid_list(vrm: dict) -> None:
    vrm["humanoid"] = ["hips", "spine"]


def _bone_string(vrm: dict) -> None:
    vrm["humanoid"]["humanBones"]["hips"] = "node 0"


def _weight_text(vrm: dict) -> None:
    vrm["expressions"]["preset"]["blink"]["morphTargetBinds"][0]["weight"] = "abc"


# Issue 51's findings, each a maker of a hostile file from a good GLB (VRM 1.0 with a
# "blink" expression for the VRM cases): name → (maker, whether it needs the VRM, the
# readers that must refuse it: an avatar is read without animations, a motion without
# its skin's matrices or VRM parts).
BOTH, AVATAR, MOTION = ("avatar", "motion"), ("avatar",), ("motion",)
GLTF_CASES: dict[str, tuple[Callable[[bytes], bytes], bool, tuple[str, ...]]] = {
    "parent cycle": (_edit(_cycle), False, BOTH),
    "node with two parents": (_edit(_two_parents), False, BOTH),
    "200,000-node chain": (_edit(_chain(200_000)), False, BOTH),
    "accessor of 10^15 elements without a buffer view": (_edit(_huge_accessor), False, BOTH),
    "sparse componentType 9999": (_edit(_sparse_type(9999)), False, BOTH),
    "sparse indices out of range": (_sparse_out_of_range, False, AVATAR),
    "animation keys from 0 to 10^12 s": (lambda d: with_animation(d, [0.0, 1e12]), False, MOTION),
    "VRM humanoid as a list": (_edit(_vrm(_humanoid_list)), True, AVATAR),
    "VRM bone entry as a string": (_edit(_vrm(_bone_string)), True, AVATAR),
    "VRM expression weight 'abc'": (_edit(_vrm(_weight_text)), True, AVATAR),
}


# --- Hypothesis: generated damage ------------------------------------------------------

SCALARS = (
    st.none()
    | st.booleans()
    | st.integers(-(2**63), 2**63)
    | st.floats(allow_nan=False)
    | st.text(max_size=20)
)
JSON_VALUES = st.recursive(
    SCALARS,
    lambda children: (
        st.lists(children, max_size=4) | st.dictionaries(st.text(max_size=8), children, max_size=4)
    ),
    max_leaves=12,
)
# Where a glTF document's values are: (top-level list, field).
GLTF_FIELDS = {
    "nodes": ("children", "mesh", "skin", "matrix", "rotation", "extras"),
    "accessors": ("count", "componentType", "type", "bufferView", "byteOffset", "sparse"),
    "bufferViews": ("byteLength", "byteOffset", "byteStride", "buffer"),
    "skins": ("joints", "inverseBindMatrices"),
    "meshes": ("primitives", "extras"),
    "buffers": ("uri",),
    "animations": ("channels", "samplers"),
}


@st.composite
def damaged_glb(draw, good: bytes) -> bytes:
    """Draw a GLB made from *good* by setting up to three of its fields to any JSON value,
    cutting it short, or flipping bytes of its binary chunk."""
    document, blob = glb_parts(good)
    for _ in range(draw(st.integers(1, 3))):
        section = draw(st.sampled_from(sorted(GLTF_FIELDS)))
        field = draw(st.sampled_from(GLTF_FIELDS[section]))
        rows = document.get(section) or [{}]
        row = rows[draw(st.integers(0, len(rows) - 1))]
        if isinstance(row, dict):
            row[field] = draw(JSON_VALUES | st.integers(0, 40))
    data = glb_pack(document, blob)
    how = draw(st.sampled_from(["as is", "cut", "flip"]))
    if how == "cut":
        return data[: draw(st.integers(0, len(data)))]
    if how == "flip":
        position = draw(st.integers(0, len(data) - 1))
        return data[:position] + bytes([data[position] ^ 0xFF]) + data[position + 1 :]
    return data


@st.composite
def damaged_text(draw, good: str) -> bytes:
    """Draw *good* text (a BVH) with lines dropped, repeated, or replaced by any text."""
    lines = good.splitlines()
    for _ in range(draw(st.integers(1, 4))):
        at = draw(st.integers(0, max(0, len(lines) - 1)))
        how = draw(st.sampled_from(["drop", "repeat", "replace", "number"]))
        if how == "drop" and lines:
            lines.pop(at)
        elif how == "repeat" and lines:
            lines[at:at] = [lines[at]] * draw(st.integers(1, 50))
        elif how == "number" and lines:
            words = lines[at].split() or [""]
            words[draw(st.integers(0, len(words) - 1))] = draw(
                st.sampled_from(["1e308", "-1", "nan", "inf", "99999999999", "0", "x"])
            )
            lines[at] = " ".join(words)
        else:
            lines.insert(at, draw(st.text(max_size=40)))
    return "\n".join(lines).encode("utf-8", "surrogatepass")


@st.composite
def damaged_bytes(draw, good: bytes) -> bytes:
    """Draw *good* bytes cut short, with bytes flipped, or with a run of any bytes."""
    data = bytearray(good)
    for _ in range(draw(st.integers(1, 4))):
        how = draw(st.sampled_from(["cut", "flip", "insert"]))
        at = draw(st.integers(0, max(0, len(data) - 1)))
        if how == "cut":
            del data[at:]
        elif how == "flip" and data:
            data[at] ^= draw(st.integers(1, 255))
        else:
            data[at:at] = draw(st.binary(min_size=1, max_size=16))
    return bytes(data)


def zip_of(members: dict[str, bytes], method: int = zipfile.ZIP_DEFLATED) -> bytes:
    """Return a zip of *members* (name → bytes)."""
    buffer = io.BytesIO()
    with zipfile.ZipFile(buffer, "w", method) as archive:
        for name, content in members.items():
            archive.writestr(name, content)
    return buffer.getvalue()


def encrypted_member_zip(name: str, content: bytes) -> bytes:
    """Return a stored zip whose one member is flagged encrypted (traditional PKWARE)."""
    data = bytearray(zip_of({name: content}, zipfile.ZIP_STORED))
    data[6] |= 0x01  # local header: general purpose flag, bit 0
    central = data.rfind(b"PK\x01\x02")
    data[central + 8] |= 0x01  # central directory: the same flag
    return bytes(data)


def corrupt_deflate_zip(name: str, content: bytes) -> bytes:
    """Return a deflated zip whose member's compressed data is damaged."""
    data = bytearray(zip_of({name: content}))
    header_end = 30 + len(name)
    for offset in range(header_end + 2, min(header_end + 40, len(data))):
        data[offset] ^= 0x5A
    return bytes(data)
