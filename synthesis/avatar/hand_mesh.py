"""The default hand-and-forearm avatar: one watertight skin over the hand model's bones.

The skin is meshed with the fingers slightly spread (the bind pose), so neighbouring
fingers do not fuse into webbing; linear blend skinning then moves it to any pose.
Radii follow an adult hand of 19 cm (finger widths after Buchholz et al. 1992, narrowing
toward the tips); fingernails are separate small meshes carried by the distal phalanges.
"""

import itertools
from functools import cache

import numpy as np
import trimesh

from synthesis.avatar.model import NAIL_RGB, SKIN_RGB, Avatar, SkinnedPart, rigid_part
from synthesis.avatar.sdf import Primitive, RoundCone, RoundedPlate, mesh_primitives, simplify
from synthesis.avatar.skinning import skin_weights
from synthesis.rigs.hand import FINGERS, HandModel
from synthesis.rigs.rig import MIRROR_X, Rig
from synthesis.skeleton.rotations import quat_rotate

# Radii (m) at the MCP, PIP, DIP and tip of each finger.
FINGER_RADII_M = {
    "index": (0.0098, 0.0088, 0.0078, 0.0068),
    "middle": (0.0100, 0.0090, 0.0080, 0.0069),
    "ring": (0.0094, 0.0085, 0.0075, 0.0066),
    "pinky": (0.0084, 0.0076, 0.0068, 0.0060),
}
# Thumb radii at the CMC, MCP, IP and tip.
THUMB_RADII_M = (0.0135, 0.0105, 0.0095, 0.0082)
# Palm outline in the wrist's frame (x toward the thumb, y toward the fingers), m, CCW.
PALM_CORNERS_M = (
    (-0.023, 0.006),
    (0.021, 0.006),
    (0.029, 0.052),
    (0.026, 0.084),
    (0.006, 0.088),
    (-0.012, 0.083),
    (-0.027, 0.071),
)
PALM_HALF_THICKNESS_M = 0.0105
# Bind pose: fingers apart so that the mesher sees separate fingers.
BIND_DEGREES = {
    "index_mcp_abduction": 7.0,
    "ring_mcp_abduction": -7.0,
    "pinky_mcp_abduction": -15.0,
    "thumb_cmc_abduction": 20.0,
}


def bind_dofs(model: HandModel) -> np.ndarray:
    """Return the bind pose of the hand avatar (radians)."""
    return model.from_degrees(BIND_DEGREES)


def hand_primitives(
    rig: Rig, dofs_rad: np.ndarray, side: str, prefix: str = ""
) -> tuple[Primitive, ...]:
    """Return the skin's primitives for a hand and forearm at a pose, in merge order.

    *rig* is the hand model or a body whose hand joints are named *prefix* + the hand
    model's names (``right_index_mcp``); the forearm runs from the joint ``forearm``.
    """
    pose = rig.pose(dofs_rad)
    positions = pose.positions_m[0]
    rotations = pose.quaternions[0]
    mirror = MIRROR_X if side == "left" else np.eye(3)

    def at(name: str) -> np.ndarray:
        return positions[rig.skeleton.index(prefix + name)]

    def axis(name: str, local) -> tuple[float, float, float]:
        vector = quat_rotate(rotations[rig.skeleton.index(prefix + name)], mirror @ local)
        return tuple(float(v) for v in vector)

    def point(name: str, local) -> tuple[float, float, float]:
        rotated = quat_rotate(rotations[rig.skeleton.index(prefix + name)], mirror @ local)
        return tuple(float(v) for v in at(name) + rotated)

    palm_normal = axis("wrist", (0.0, 0.0, 1.0))
    corners = PALM_CORNERS_M
    if side == "left":
        # Mirroring flips the polygon's winding: walk it the other way.
        corners = tuple((-x, y) for x, y in reversed(corners))
    primitives: list[Primitive] = [
        RoundCone(
            prefix + "forearm",
            point("forearm", (0.0, 0.02, 0.0)),
            point("wrist", (0.0, -0.012, 0.0)),
            0.036,
            0.027,
            flatten=0.72,
            normal=palm_normal,
        ),
        RoundedPlate(
            prefix + "wrist",
            point("wrist", (0.0, 0.0, 0.001)),
            axis("wrist", (1.0, 0.0, 0.0)),
            axis("wrist", (0.0, 1.0, 0.0)),
            corners,
            PALM_HALF_THICKNESS_M,
            blend_m=0.016,
        ),
        # The thenar eminence rides on the thumb's metacarpal.
        RoundCone(
            prefix + "thumb_cmc",
            point("wrist", (0.012, 0.018, 0.004)),
            tuple(at("thumb_mcp")),
            THUMB_RADII_M[0],
            THUMB_RADII_M[1],
            blend_m=0.012,
        ),
    ]
    return tuple(primitives) + _digits(at, prefix)


def _digits(at, prefix: str) -> tuple[RoundCone, ...]:
    """Return the phalanges of the thumb and the fingers, *at* giving a joint's position."""
    primitives = []
    thumb = ("thumb_mcp", "thumb_ip", "thumb_tip")
    for k, (start, end) in enumerate(itertools.pairwise(thumb)):
        radii = THUMB_RADII_M[k + 1 : k + 3]
        primitives.append(_phalanx(prefix + start, at(start), at(end), radii, k))
    for finger in FINGERS:
        radii = FINGER_RADII_M[finger]
        joints = (f"{finger}_mcp", f"{finger}_pip", f"{finger}_dip", f"{finger}_tip")
        for k, (start, end) in enumerate(itertools.pairwise(joints)):
            primitives.append(_phalanx(prefix + start, at(start), at(end), radii[k : k + 2], k))
    return tuple(primitives)


def _phalanx(joint: str, start, end, radii, k: int) -> RoundCone:
    start, end = np.asarray(start), np.asarray(end)
    if k == 2 or joint.endswith("thumb_ip"):
        # The fingertip's pad ends at the tip landmark, not a radius beyond it.
        direction = (end - start) / np.linalg.norm(end - start)
        end = end - 0.75 * radii[1] * direction
    return RoundCone(
        joint,
        tuple(float(v) for v in start),
        tuple(float(v) for v in end),
        radii[0],
        radii[1],
        # The first phalanx blends into the palm; the others into their neighbour.
        blend_m=0.006 if k == 0 else 0.003,
    )


def hand_nails(
    rig: Rig, dofs_rad: np.ndarray, side: str, prefix: str = "", radii_m: dict | None = None
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Return nail meshes (vertices, faces) and each vertex's bone, at a pose.

    *radii_m* gives each digit's radius at its nail (this skin's by default).
    """
    pose = rig.pose(dofs_rad)
    mirror = MIRROR_X if side == "left" else np.eye(3)
    radii = {
        **{f: FINGER_RADII_M[f][3] for f in FINGERS},
        "thumb": THUMB_RADII_M[3],
        **(radii_m or {}),
    }
    vertices, faces, owners = [], [], []
    offset = 0
    for finger, joint, tip, radius in [
        *((f, f"{f}_dip", f"{f}_tip", radii[f]) for f in FINGERS),
        ("thumb", "thumb_ip", "thumb_tip", radii["thumb"]),
    ]:
        index = rig.skeleton.index(prefix + joint)
        rotation = pose.quaternions[0, index]
        base = pose.positions_m[0, index]
        end = pose.positions_m[0, rig.skeleton.index(prefix + tip)]
        length = np.linalg.norm(end - base)
        nail = trimesh.creation.icosphere(subdivisions=1)
        scale = np.array([radius * 0.68, length * 0.3, radius * 0.16])
        local = nail.vertices * scale + np.array([0.0, length * 0.5, -radius * 0.9])
        if finger == "thumb":
            local[:, 1] -= length * 0.05
        world = base + quat_rotate(rotation, local @ mirror.T)
        vertices.append(world)
        faces.append(nail.faces + offset)
        owners.append(np.full(len(world), index))
        offset += len(world)
    faces_all = np.concatenate(faces)
    if side == "left":
        faces_all = faces_all[:, ::-1]
    return np.concatenate(vertices), faces_all, np.concatenate(owners)


@cache
def hand_avatar(side: str = "right", voxel_mm: float = 1.2, max_faces: int = 20000) -> Avatar:
    """Return the hand-and-forearm avatar (built once per engine version, then kept on disk
    by :mod:`synthesis.avatar.store`, and once per process in memory)."""
    from synthesis.avatar.store import cached_avatar

    return cached_avatar(
        f"hand-{side}-{voxel_mm:g}mm-{max_faces}",
        HandModel(side),
        lambda: _build_hand_avatar(side, voxel_mm, max_faces),
    )


def _build_hand_avatar(side: str, voxel_mm: float, max_faces: int) -> Avatar:
    """Build the hand-and-forearm avatar."""
    model = HandModel(side)
    bind = bind_dofs(model)
    primitives = hand_primitives(model, bind, side)
    vertices, faces = mesh_primitives(primitives, voxel_mm / 1000)
    vertices, faces = simplify(vertices, faces, max_faces)
    vertices = np.asarray(vertices, dtype=np.float64)
    index = {name: i for i, name in enumerate(model.skeleton.names)}
    skin = SkinnedPart(
        "skin",
        vertices,
        np.asarray(faces, dtype=np.int64),
        np.broadcast_to(np.asarray(SKIN_RGB), vertices.shape),
        skin_weights(vertices, primitives, index),
    )
    nails = rigid_part("nails", *hand_nails(model, bind, side), NAIL_RGB, casts_shadow=False)
    return Avatar(f"hand-{side}", model, bind, (skin, nails))
