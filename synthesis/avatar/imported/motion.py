"""Read third-party motion: a glTF animation, or FBX (and the other formats Debian's
assimp reads) converted to glTF by assimp's command line, as a BVH-like Motion.

The skeleton is the skin's joints (else the animated nodes and their ancestors); each
joint's local rotation at each frame comes from the animation, sampled at a fixed rate
(linear keys slerped, step keys held, cubic-spline keys at their values), as Euler
angles in BVH's ZXY order; its offset is its rest translation. What lies above the
skeleton's root in the node tree (an FBX's unit scale and its Z-up turn) is folded into
the root, so the motion is in metres, Y up, as the engine's. The motion then goes to
:func:`synthesis.rigs.retarget.retarget` as a BVH file's would.
"""

import shutil
import subprocess
import tempfile
from collections.abc import Mapping
from pathlib import Path

import numpy as np
from scipy.spatial.transform import Rotation, Slerp

from synthesis.avatar.imported.gltf_read import (
    DAMAGE,
    GltfError,
    Reader,
    damaged,
    files_beside,
    load,
)
from synthesis.skeleton.motion import Motion
from synthesis.skeleton.skeleton import Joint, Skeleton

ASSIMP_TIMEOUT_S = 300
GLTF_SUFFIXES = (".glb", ".gltf", ".vrm")
# What assimp 5 reads that motion comes in (its command line converts them to glTF).
ASSIMP_SUFFIXES = (".fbx", ".dae", ".x", ".ms3d", ".b3d", ".smd")
DEFAULT_RATE_HZ = 30.0
# The longest motion brought in, as the longest uploaded clip (a hostile file's keys
# from 0 to 10¹² s once asked for petabytes of frames).
MAX_DURATION_S = 600.0
ROOT_CHANNELS = ("Xposition", "Yposition", "Zposition", "Zrotation", "Xrotation", "Yrotation")
JOINT_CHANNELS = ("Zrotation", "Xrotation", "Yrotation")


def assimp_to_glb(path: str | Path) -> bytes:
    """Return the file at *path* converted to GLB by assimp's command line (Debian's
    ``assimp-utils``); GltfError names what went wrong."""
    command = shutil.which("assimp")
    if command is None:
        raise GltfError(
            "assimp is not installed (Debian's assimp-utils; make install adds "
            "it): FBX and the other formats it reads cannot come in."
        )
    with tempfile.TemporaryDirectory() as folder:
        out = Path(folder) / "converted.glb"
        try:
            done = subprocess.run(
                [command, "export", str(path), str(out), "-fglb2"],
                capture_output=True,
                timeout=ASSIMP_TIMEOUT_S,
            )
        except subprocess.TimeoutExpired:
            raise GltfError(
                f"assimp took over {ASSIMP_TIMEOUT_S} s on {Path(path).name}."
            ) from None
        if done.returncode != 0 or not out.is_file():
            why = (done.stderr or done.stdout).decode(errors="replace").strip().splitlines()
            raise GltfError(
                f"assimp cannot read {Path(path).name}: {why[-1] if why else 'no reason given'}."
            )
        return out.read_bytes()


def _joints(reader: Reader) -> list[int]:
    """Return the skeleton's nodes: the first skin's joints and every node the animation
    turns or moves (assimp hangs a BVH's root on a mesh node, outside the skin), with the
    nodes between two of them."""
    gltf = reader.gltf
    members = {
        c.target.node
        for a in gltf.animations
        for c in a.channels
        if c.target.path in ("rotation", "translation")
    }
    if gltf.skins:
        members |= set(gltf.skins[0].joints)
    nearest = reader.nearest_ancestors(members)
    between = set()
    for node in members:
        up = reader.parent.get(node)
        # The nodes on the way up to the nearest member, where there is one.
        while up is not None and up not in members and nearest[node] is not None:
            if up in between:
                break  # the rest of the way up is in already
            between.add(up)
            up = reader.parent.get(up)
    return sorted(members | between)


def _tracks(reader: Reader, animation) -> dict:
    """Return each animated (node, path)'s key times, values and interpolation."""
    tracks = {}
    for channel in animation.channels:
        if channel.target.path == "weights":
            # Morph weights (a face's blendshapes) are no joint's motion; each key holds
            # one value per target, which the count check below would take for damage.
            continue
        sampler = animation.samplers[channel.sampler]
        times = reader.read(sampler.input)[:, 0]
        values = reader.read(sampler.output)
        interpolation = sampler.interpolation or "LINEAR"
        per_key = 3 if interpolation == "CUBICSPLINE" else 1  # in-tangent, value, out-tangent
        if not len(times) or len(values) != per_key * len(times):
            raise GltfError(
                f"{reader.source}: an animation sampler has {len(values)} values for "
                f"{len(times)} keys."
            )
        if not np.isfinite(times).all() or (np.diff(times) < 0).any():
            raise GltfError(f"{reader.source}: an animation's key times are not increasing.")
        if times[-1] - times[0] > MAX_DURATION_S:
            raise GltfError(
                f"{reader.source}: the animation lasts {times[-1] - times[0]:.0f} s; motion "
                f"comes in up to {MAX_DURATION_S:.0f} s."
            )
        if per_key == 3:
            values = values.reshape(len(times), 3, -1)[:, 1]
        tracks[(channel.target.node, channel.target.path)] = (times, values, interpolation)
    return tracks


def _sample(track, times: np.ndarray, rotation: bool) -> np.ndarray:
    keys, values, interpolation = track
    if len(keys) == 1:
        return np.repeat(values[:1], len(times), axis=0)
    clipped = np.clip(times, keys[0], keys[-1])
    if interpolation == "STEP":
        return values[np.clip(np.searchsorted(keys, clipped, side="right") - 1, 0, None)]
    if rotation:
        return Slerp(keys, Rotation.from_quat(values))(clipped).as_quat()
    return np.column_stack([np.interp(clipped, keys, values[:, k]) for k in range(values.shape[1])])


def _rate(tracks: dict, rate_hz: float | None) -> tuple[np.ndarray, float]:
    """Return the frame times to sample and their rate (the keys' own rate, at most
    120 Hz, when *rate_hz* is None)."""
    keys = np.unique(np.concatenate([t[0] for t in tracks.values()]))
    steps = np.diff(keys)
    if rate_hz is None:
        shortest = steps[steps > 1e-6].min() if (steps > 1e-6).any() else 1 / DEFAULT_RATE_HZ
        rate_hz = float(min(120.0, max(1.0, round(1.0 / shortest))))
    return np.arange(keys[0], keys[-1] + 0.5 / rate_hz, 1.0 / rate_hz), rate_hz


def _parents_first(reader: Reader, nodes: list[int]) -> list[int]:
    """Return *nodes* ordered so that each comes after its parent, as BVH lists joints."""
    members, order, placed = set(nodes), [], set()
    for node in nodes:
        chain, up = [], node
        while up is not None and up in members and up not in placed:
            chain.append(up)
            up = reader.parent.get(up)
        order.extend(reversed(chain))
        placed.update(chain)
    return order


def _local(tracks: dict, node, n, times: np.ndarray) -> tuple[np.ndarray, Rotation]:
    """Return a node's local translations and rotations at *times* (its rest where the
    animation leaves it)."""
    frames = len(times)
    if (node, "translation") in tracks:
        translation = _sample(tracks[(node, "translation")], times, False)
    else:
        rest = n.translation if n.translation is not None else (0, 0, 0)
        translation = np.repeat(np.asarray(rest, float)[None], frames, axis=0)
    if (node, "rotation") in tracks:
        quaternions = _sample(tracks[(node, "rotation")], times, True)
    else:
        rest = n.rotation if n.rotation is not None else (0, 0, 0, 1)
        quaternions = np.repeat(np.asarray(rest, float)[None], frames, axis=0)
    return translation, Rotation.from_quat(quaternions)


def read_gltf_motion(
    data: bytes,
    source: str = "the file",
    rate_hz: float | None = None,
    resources: Mapping[str, bytes] | None = None,
) -> Motion:
    """Return the first animation of glTF *data* as a Motion sampled at *rate_hz*
    (the keys' own rate, at most 120 Hz, when None); *resources* are a ``.gltf``'s
    separate buffer files (:func:`~synthesis.avatar.imported.gltf_read.load`)."""
    try:
        return _read_motion(data, source, rate_hz, resources)
    except GltfError:
        raise
    except DAMAGE as error:  # keys scipy cannot turn (zero quaternions, wrong widths), …
        raise damaged(source, "animation", error) from None


def _read_motion(
    data: bytes, source: str, rate_hz: float | None, resources: Mapping[str, bytes] | None
) -> Motion:
    gltf, buffers = load(data, source, resources)
    reader = Reader(gltf, buffers, source)
    if not gltf.animations:
        raise GltfError(f"{source} has no animation: there is no motion to bring in.")
    nodes = _parents_first(reader, _joints(reader))
    if not nodes:
        raise GltfError(f"{source}'s animation moves no skeleton.")
    tracks = _tracks(reader, gltf.animations[0])
    times, rate_hz = _rate(tracks, rate_hz)
    return _sampled(reader, nodes, tracks, times, rate_hz)


def _sampled(
    reader: Reader, nodes: list[int], tracks: dict, times: np.ndarray, rate_hz: float
) -> Motion:
    """Return the skeleton of *nodes* moved by *tracks* at *times* as a Motion."""
    gltf = reader.gltf
    joints, columns, scale = [], [], 1.0
    position = {node: k for k, node in enumerate(nodes)}
    names: set[str] = set()
    for index, node in enumerate(nodes):
        parent = reader.parent.get(node)
        parent_index = position.get(parent, -1)
        translation, rotation = _local(tracks, node, gltf.nodes[node], times)
        if parent_index < 0:  # fold what lies above the skeleton into its root
            above = reader.world_matrix(parent) if parent is not None else np.eye(4)
            scale = float(np.cbrt(abs(np.linalg.det(above[:3, :3])))) or 1.0
            turn = Rotation.from_matrix(above[:3, :3] / scale)
            translation = turn.apply(translation) * scale + above[:3, 3]
            rotation = turn * rotation
            channels = ROOT_CHANNELS
            columns.append(np.column_stack([translation, rotation.as_euler("ZXY", degrees=True)]))
            # The channels hold the root's whole position, so no offset: our kinematics
            # adds the two (assimp's sample simple_skin.gltf stood at twice its height),
            # and Blender's BVH importer takes the channels alone; at zero both agree.
            offset = np.zeros(3)
        else:
            channels = JOINT_CHANNELS
            columns.append(rotation.as_euler("ZXY", degrees=True))
            offset = translation[0] * scale
        name = gltf.nodes[node].name or f"joint_{index}"
        unique = name if name not in names else f"{name}_{index}"
        names.add(unique)
        joints.append(Joint(unique, parent_index, tuple(float(v) for v in offset), channels))
    skeleton = Skeleton(tuple(joints), length_unit="m")
    return Motion(skeleton, np.concatenate(columns, axis=1), 1.0 / rate_hz)


def read_motion_file(path: str | Path, rate_hz: float | None = None) -> Motion:
    """Return the motion of a BVH, glTF/GLB/VRM, or (through assimp) FBX file at *path*."""
    from synthesis.skeleton.bvh import read_bvh
    from synthesis.skeleton.retime import resample

    path = Path(path)
    suffix = path.suffix.lower()
    if suffix == ".bvh":
        motion = read_bvh(path)
        return (
            resample(motion, rate_hz)
            if rate_hz and abs(motion.rate_hz - rate_hz) > 1e-9
            else motion
        )
    if suffix in GLTF_SUFFIXES:
        data = path.read_bytes()
        # A .gltf on the command line may keep its buffers in files beside it.
        resources = files_beside(path, data) if suffix == ".gltf" else None
        return read_gltf_motion(data, path.name, rate_hz, resources)
    if suffix in ASSIMP_SUFFIXES:
        return read_gltf_motion(assimp_to_glb(path), path.name, rate_hz)
    raise GltfError(
        f"{path.name}: motion comes in as BVH, glTF/GLB/VRM or, through assimp, "
        f"{', '.join(s.lstrip('.').upper() for s in ASSIMP_SUFFIXES)}."
    )
