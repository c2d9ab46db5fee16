"""The human avatar's face and features: blendshapes, brows and hair, eyes, nails.

The ARKit blendshapes of the Face Units pack move the skin and MakeHuman's helper meshes
(lashes, teeth, tongue); brows and a close-cropped hair cap are shells over the skin
(:mod:`~synthesis.avatar.human.parts`) that take its weights and blendshapes; eyeballs
turn with the rig's eye joints; nails sit on the digits' last bones.
"""

from dataclasses import replace

import numpy as np
import trimesh

from synthesis.avatar.hand_mesh import hand_nails
from synthesis.avatar.human import assets
from synthesis.avatar.human.body import Warped, quad_triangles
from synthesis.avatar.human.face import CHANNELS
from synthesis.avatar.human.fit import DIGITS, digit_joints
from synthesis.avatar.human.parts import brow_distance, eyeball, hair_distance, shell
from synthesis.avatar.model import NAIL_RGB, SkinnedPart, merge_parts, rigid_part
from synthesis.avatar.skinning import Morphs, SkinWeights
from synthesis.rigs.body import SIDES, BodyModel
from synthesis.rigs.rig import MIRROR_X
from synthesis.skeleton.rotations import quat_to_matrix

HAIR_RGB = (0.055, 0.045, 0.04)
SCLERA_RGB, IRIS_RGB, PUPIL_RGB = (0.88, 0.86, 0.83), (0.30, 0.19, 0.10), (0.02, 0.02, 0.02)
TEETH_RGB, TONGUE_RGB = (0.86, 0.83, 0.76), (0.62, 0.30, 0.30)
# Shells lifted off the skin: the brows a little, the hair cap more.
BROW_LIFT_M, HAIR_LIFT_M = 0.0009, 0.0025
# The eyeball's radius before the head's scale (MakeHuman's eye sockets').
EYE_RADIUS_M = 0.0118


def _normals(vertices: np.ndarray, faces: np.ndarray) -> np.ndarray:
    return np.asarray(trimesh.Trimesh(vertices, faces, process=False).vertex_normals)


def face_morphs(
    indices: np.ndarray, vertices: np.ndarray, faces: np.ndarray, scale: float
) -> Morphs:
    """Return the ARKit blendshapes of the mesh vertices *indices* (base-mesh numbers),
    whose warped positions are *vertices*, offsets scaled by the head's *scale*."""
    row = {int(v): k for k, v in enumerate(indices)}
    names = tuple(CHANNELS)
    offsets = np.zeros((len(names), len(indices), 3))
    for k, name in enumerate(names):
        moved, delta = assets.face_target(name)
        for vertex, offset in zip(moved, delta, strict=True):
            if int(vertex) in row:
                offsets[k, row[int(vertex)]] = scale * offset
    touched = np.flatnonzero(np.abs(offsets).sum(axis=(0, 2)) > 0)
    base = _normals(vertices, faces)
    normal_offsets = np.stack(
        [_normals(vertices + offsets[k], faces)[touched] - base[touched] for k in range(len(names))]
    )
    return Morphs(names, touched, offsets[:, touched], normal_offsets)


def _rows_of(morphs: Morphs, rows: np.ndarray) -> Morphs:
    """Return the blendshapes of a mesh made of the given rows of *morphs*' mesh."""
    where = {int(v): k for k, v in enumerate(morphs.vertices)}
    inside = [(k, where[int(r)]) for k, r in enumerate(rows) if int(r) in where]
    mine = np.array([k for k, _ in inside], dtype=np.intp)
    theirs = np.array([t for _, t in inside], dtype=np.intp)
    return Morphs(morphs.names, mine, morphs.offsets_m[:, theirs], morphs.normal_offsets[:, theirs])


def features(warped: Warped, skin: SkinnedPart, head_joint: int) -> SkinnedPart:
    """Return the brows, hair cap, lashes, teeth and tongue as one part.

    Brows and hair are shells over the skin's faces that reach into them, coloured
    across a smooth edge (a signed distance, :class:`SkinnedPart`): skin outside it, so
    that their outlines run through the faces instead of along them.
    """
    scale = warped.head.linear[0, 0]
    on_head = (skin.weights.joints[:, 0] == head_joint)[skin.faces].all(axis=1)
    brow = np.min(
        [brow_distance(skin.vertices_m, eye, scale=scale) for eye in warped.eyes_m], axis=0
    )
    hair = np.maximum(hair_distance(skin.vertices_m, warped.eyes_m, scale), -brow)
    skin_rgb = np.asarray(skin.colors_rgb[0])
    parts = []
    for distance, lift in ((brow, BROW_LIFT_M), (hair, HAIR_LIFT_M)):
        chosen = on_head & (distance[skin.faces] < 0).any(axis=1)
        vertices, faces, rows = shell(skin.vertices_m, skin.normals, skin.faces, chosen, lift)
        parts.append(
            SkinnedPart(
                "shell",
                vertices,
                faces,
                np.broadcast_to(skin_rgb, (len(vertices), 3)),
                SkinWeights(skin.weights.joints[rows], skin.weights.weights[rows]),
                skin.normals[rows],
                edge_m=distance[rows],
                across_rgb=np.broadcast_to(HAIR_RGB, (len(vertices), 3)),
                morphs=_rows_of(skin.morphs, rows),
            )
        )
    mesh = assets.base_mesh()
    for name, (indices, vertices) in warped.helpers.items():
        faces = quad_triangles(mesh.quads, indices)
        colour = HAIR_RGB if "lashes" in name else TONGUE_RGB if "tongue" in name else TEETH_RGB
        part = rigid_part(name, vertices, faces, np.full(len(vertices), head_joint), colour)
        parts.append(replace(part, morphs=face_morphs(indices, vertices, faces, scale)))
    return merge_parts("features", parts, casts_shadow=False)


def eyes(warped: Warped) -> SkinnedPart:
    names = warped.rig.skeleton.names
    parts = []
    for side, centre in zip(("right", "left"), warped.eyes_m, strict=True):
        radius = EYE_RADIUS_M * warped.head.linear[0, 0]
        vertices, faces, colours = eyeball(
            centre, radius, (0.0, 0.0, 1.0), SCLERA_RGB, IRIS_RGB, PUPIL_RGB
        )
        owner = np.full(len(vertices), names.index(f"{side}_eye"))
        part = rigid_part(f"{side} eye", vertices, faces, owner, (0.0, 0.0, 0.0), False)
        parts.append(replace(part, colors_rgb=colours))
    return merge_parts("eyes", parts, casts_shadow=False)


def nail_radii(
    rig: BodyModel, bind_dofs_rad: np.ndarray, skin: SkinnedPart, side: str
) -> dict[str, float]:
    """Return each digit's depth (m) from its last bone to the back of its skin, halfway
    along the bone: where :func:`hand_nails` lays the nail."""
    pose = rig.pose(bind_dofs_rad)
    owner = skin.weights.main_joints()
    mirror = MIRROR_X if side == "left" else np.eye(3)
    radii = {}
    for digit in DIGITS:
        joints = digit_joints(digit)
        index = rig.skeleton.index(f"{side}_{joints[2]}")
        tip = pose.positions_m[0, rig.skeleton.index(f"{side}_{joints[3]}")]
        base = pose.positions_m[0, index]
        rotation = quat_to_matrix(pose.quaternions[0, index])
        local = ((skin.vertices_m[owner == index] - base) @ rotation) @ mirror
        length = np.linalg.norm(tip - base)
        middle = (local[:, 1] > 0.3 * length) & (local[:, 1] < 0.7 * length)
        radii[digit] = float(np.percentile(-local[middle, 2], 90))
    return radii


def nails(rig: BodyModel, bind_dofs_rad: np.ndarray, skin: SkinnedPart) -> SkinnedPart:
    nails = []
    for side in SIDES:
        radii = nail_radii(rig, bind_dofs_rad, skin, side)
        mesh = hand_nails(rig, bind_dofs_rad, side, side + "_", radii)
        nails.append(rigid_part(f"{side} nails", *mesh, NAIL_RGB, casts_shadow=False))
    return merge_parts("nails", nails, casts_shadow=False)
