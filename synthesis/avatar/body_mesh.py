"""The default upper-body avatar: torso, neck, head, arms and both hands in one skin.

A plain dark long-sleeved top against skin-coloured hands, neck and face, the signing
video convention (spec 01), with a face that moves (synthesis.avatar.face_mesh). The
skin is meshed at the bind pose (arms lifted away from the torso, fingers
apart) so that limbs do not fuse with the body, then decimated for rendering speed.
"""

from functools import cache

import numpy as np

from synthesis.avatar.face_mesh import face_part, face_skin_weights
from synthesis.avatar.hand_mesh import BIND_DEGREES as HAND_BIND_DEGREES
from synthesis.avatar.hand_mesh import hand_nails, hand_primitives
from synthesis.avatar.model import (
    NAIL_RGB,
    SKIN_RGB,
    TOP_RGB,
    Avatar,
    SkinnedPart,
    merge_parts,
    rigid_part,
)
from synthesis.avatar.sdf import Primitive, RoundCone, mesh_primitives, simplify
from synthesis.avatar.skinning import skin_weights
from synthesis.rigs.body import SIDES, BodyModel
from synthesis.skeleton.rotations import quat_rotate

# Bones under the top; the forearm's sleeve ends this far from the wrist.
CLOTHED = ("hips", "spine_lower", "spine_middle", "spine_upper", "clavicle", "shoulder", "elbow")
CUFF_M = 0.065
# The neckline: a circle this far below the neck joint, of this radius about the neck,
# across the bones that meet there.
COLLAR_BELOW_NECK_M = 0.03
COLLAR_RADIUS_M = 0.075
COLLARED = ("spine_upper", "neck", "right_clavicle", "left_clavicle")


def bind_dofs(model: BodyModel) -> np.ndarray:
    """Return the bind pose: arms 35° away from the body, elbows a little bent, hands apart."""
    degrees = {}
    for side in SIDES:
        degrees[f"{side}_shoulder_abduction"] = 35.0
        degrees[f"{side}_elbow_flexion"] = 20.0
        degrees.update({f"{side}_{k}": v for k, v in HAND_BIND_DEGREES.items()})
    return model.from_degrees(degrees)


def body_primitives(model: BodyModel, dofs_rad: np.ndarray) -> tuple[Primitive, ...]:
    """Return the skin's primitives for the upper body at a pose, in merge order."""
    pose = model.pose(dofs_rad)

    def point(joint: str, local=(0.0, 0.0, 0.0)) -> tuple[float, float, float]:
        index = model.skeleton.index(joint)
        moved = quat_rotate(pose.quaternions[0, index], np.asarray(local, dtype=np.float64))
        return tuple(float(v) for v in pose.positions_m[0, index] + moved)

    forward = (0.0, 0.0, 1.0)
    primitives: list[Primitive] = [
        RoundCone(
            "hips",
            point("hips", (0, -0.06, 0)),
            point("spine_lower"),
            0.145,
            0.135,
            flatten=0.62,
            normal=forward,
        ),
        RoundCone(
            "spine_lower",
            point("spine_lower"),
            point("spine_middle"),
            0.135,
            0.14,
            blend_m=0.05,
            flatten=0.6,
            normal=forward,
        ),
        RoundCone(
            "spine_middle",
            point("spine_middle"),
            point("spine_upper"),
            0.14,
            0.15,
            blend_m=0.05,
            flatten=0.62,
            normal=forward,
        ),
        RoundCone(
            "spine_upper",
            point("spine_upper"),
            point("spine_upper", (0, 0.115, -0.01)),
            0.15,
            0.11,
            blend_m=0.05,
            flatten=0.6,
            normal=forward,
        ),
    ]
    for side in SIDES:
        p = side + "_"
        primitives += [
            RoundCone(
                p + "clavicle",
                point(p + "clavicle", (0, -0.01, -0.02)),
                point(p + "shoulder", (0, 0.015, 0)),
                0.055,
                0.052,
                blend_m=0.05,
            ),
            RoundCone(
                p + "shoulder", point(p + "shoulder"), point(p + "elbow"), 0.05, 0.04, blend_m=0.04
            ),
        ]
    primitives += [
        RoundCone("neck", point("neck", (0, -0.02, 0)), point("head"), 0.054, 0.05, blend_m=0.03),
        RoundCone(
            "head",
            point("head", (0, 0.07, 0.0)),
            point("head", (0, 0.125, -0.005)),
            0.088,
            0.09,
            blend_m=0.03,
            flatten=0.84,
            normal=(1.0, 0.0, 0.0),
        ),
        RoundCone(
            "head",
            point("head", (0, 0.07, 0.02)),
            point("head", (0, 0.015, 0.062)),
            0.06,
            0.03,
            blend_m=0.03,
            flatten=0.9,
            normal=(1.0, 0.0, 0.0),
        ),
        RoundCone(
            "head",
            point("head", (0, 0.1, 0.085)),
            point("head", (0, 0.068, 0.1)),
            0.011,
            0.013,
            blend_m=0.012,
        ),
    ]
    for side in SIDES:
        primitives += hand_primitives(model, dofs_rad, side, prefix=side + "_")
    return tuple(primitives)


def clothing_colours(
    model: BodyModel, vertices_m: np.ndarray, weights, dofs_rad, skin_rgb=SKIN_RGB, top_rgb=TOP_RGB
):
    """Return the skin's colour edge (see SkinnedPart): skin colour, the signed distance
    (m) into the skin from the edge of the top, and the top's colour.

    The neckline is a circle round the neck and each cuff a plane across the forearm, so
    their edges run straight through the decimated mesh's large triangles (a colour per
    vertex drew those triangles' ragged edges along the neckline and the wrists).
    """
    names = model.skeleton.names
    dominant = weights.main_joints()
    clothed = np.array([any(name.endswith(c) for c in CLOTHED) for name in names])[dominant]
    # Signed distance (m) into the skin from the edge of the top: negative under cloth.
    into_skin = np.where(clothed, -np.inf, np.inf)
    positions = model.pose(dofs_rad).positions_m[0]
    neck = positions[model.skeleton.index("neck")]
    up = positions[model.skeleton.index("head")] - neck
    up /= np.linalg.norm(up)
    relative = vertices_m - neck
    height = relative @ up - COLLAR_BELOW_NECK_M
    radial = np.linalg.norm(relative - np.outer(relative @ up, up), axis=1)
    collar = np.minimum(height, COLLAR_RADIUS_M - radial)
    trunk = np.isin(dominant, [model.skeleton.index(n) for n in COLLARED])
    into_skin[trunk] = collar[trunk]
    for side in SIDES:
        forearm = model.skeleton.index(f"{side}_forearm")
        wrist = positions[model.skeleton.index(f"{side}_wrist")]
        elbow = positions[forearm]
        along = (vertices_m - wrist) @ (elbow - wrist) / np.linalg.norm(elbow - wrist)
        on_forearm = dominant == forearm
        into_skin[on_forearm] = CUFF_M - along[on_forearm]
    n = len(vertices_m)
    # Far from any edge the distance only needs its sign.
    return (
        np.broadcast_to(np.asarray(skin_rgb), (n, 3)),
        np.clip(into_skin, -1.0, 1.0),
        np.broadcast_to(np.asarray(top_rgb), (n, 3)),
    )


@cache
def body_avatar(dominant: str = "right", voxel_mm: float = 2.5, max_faces: int = 20000) -> Avatar:
    """Return the upper-body avatar (built once per engine version, then kept on disk by
    :mod:`synthesis.avatar.store`, and once per process in memory).

    The skin is decimated to *max_faces* triangles: at the signing view's 640×480, hands
    and face look alike at 20,000 and 35,000 (the face's features are parts of their
    own), and 20,000 render the frame about a sixth faster (bench/bench_render.py).
    """
    from synthesis.avatar.store import cached_avatar

    return cached_avatar(
        f"upper-body-{dominant}-{voxel_mm:g}mm-{max_faces}",
        BodyModel(dominant),
        lambda: _build_body_avatar(dominant, voxel_mm, max_faces),
    )


def _build_body_avatar(dominant: str, voxel_mm: float, max_faces: int) -> Avatar:
    """Build the upper-body avatar."""
    model = BodyModel(dominant)
    bind = bind_dofs(model)
    primitives = body_primitives(model, bind)
    vertices, faces = mesh_primitives(primitives, voxel_mm / 1000)
    vertices, faces = simplify(vertices, faces, max_faces)
    vertices = np.asarray(vertices, dtype=np.float64)
    index = {name: i for i, name in enumerate(model.skeleton.names)}
    weights = face_skin_weights(model, bind, vertices, skin_weights(vertices, primitives, index))
    colours, edge_m, across_rgb = clothing_colours(model, vertices, weights, bind)
    skin = SkinnedPart(
        "skin",
        vertices,
        np.asarray(faces, dtype=np.int64),
        colours,
        weights,
        edge_m=edge_m,
        across_rgb=across_rgb,
    )
    # Three parts, three draw calls a pass: pyrender's per-draw overhead in Python was a
    # tenth of a frame with the face's features and each hand's nails apart.
    nails = merge_parts(
        "nails",
        [
            rigid_part(f"{side} nails", *hand_nails(model, bind, side, side + "_"), NAIL_RGB)
            for side in SIDES
        ],
        casts_shadow=False,
    )
    return Avatar(
        f"upper-body-{dominant}", model, bind, (skin, face_part(model, bind, primitives), nails)
    )
