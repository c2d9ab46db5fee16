"""MakeHuman's body on the engine's rig at its bind pose: the warped skin and its weights.

The base mesh is shaped (:mod:`~synthesis.avatar.human.phenotype`), its skeleton placed
(:mod:`~.skeleton`), the engine's rig posed like it (:mod:`~.fit`) and every vertex moved
onto the engine's skeleton (:mod:`~.warp`). The skin's weights are MakeHuman's, each bone's
given to the engine joint that carries it; a digit's are laid out again along the
engine's joints of the digit.
"""

from dataclasses import dataclass

import numpy as np

from synthesis.avatar.human import assets
from synthesis.avatar.human.fit import (
    DIGITS,
    chain_shares,
    correspondence,
    digit_joints,
    fit_bind_dofs,
    joint_points,
    palm_frame,
)
from synthesis.avatar.human.parts import sphere_fit
from synthesis.avatar.human.phenotype import Phenotype, body_phenotype, shaped_vertices
from synthesis.avatar.human.skeleton import SIDE_SUFFIX, engine_joint, place_skeleton
from synthesis.avatar.human.warp import (
    Affine,
    TrunkWarp,
    blend_warp,
    chain_position,
    digit_transforms,
    frame_affine,
    segment_affine,
)
from synthesis.avatar.skinning import SkinWeights, strongest_weights
from synthesis.rigs.body import SIDES, BodyModel

# The mesh is cut this far below the pelvis (the signing view never shows the legs).
CUT_BELOW_PELVIS_M = 0.32
# A digit's weights cross over between two engine joints over this share of its length.
DIGIT_BLEND_SHARE = 0.06
# The digits thickened to the engine hand's (the alphabet's contacts were solved with its radii).
DIGIT_GIRTH = 1.12
TRUNK_JOINTS = frozenset({"hips", "spine_lower", "spine_middle", "spine_upper", "neck"})
# MakeHuman's helper meshes the face uses (its targets move them): lashes, teeth, tongue.
HELPERS = (
    "helper-r-eyelashes-2",
    "helper-l-eyelashes-2",
    "helper-r-eyelashes-1",
    "helper-l-eyelashes-1",
    "helper-upper-teeth",
    "helper-lower-teeth",
    "helper-tongue",
)


@dataclass(frozen=True)
class Warped:
    """MakeHuman's body on the engine's rig at its bind pose."""

    rig: BodyModel
    bind_dofs_rad: np.ndarray
    skin_vertices: np.ndarray
    skin_faces: np.ndarray
    kept: np.ndarray
    weights: SkinWeights
    head: Affine
    eyes_m: np.ndarray
    helpers: dict


def bone_weights(weights: dict, kept: np.ndarray) -> dict:
    """Return each bone's (row in *kept*, weight) for the kept vertices."""
    row = np.full(int(kept.max()) + 1, -1)
    row[kept] = np.arange(len(kept))
    table = {}
    for bone, pairs in weights.items():
        pairs = np.array(pairs, dtype=np.float64).reshape(-1, 2)
        indices = pairs[:, 0].astype(np.intp)
        inside = indices < len(row)
        rows, values = row[indices[inside]], pairs[inside, 1]
        chosen = (rows >= 0) & (values > 0)
        if chosen.any():
            table[bone] = (rows[chosen], values[chosen])
    return table


def quad_triangles(quads: np.ndarray, kept: np.ndarray) -> np.ndarray:
    """Return the quads whose corners are all kept, as triangles in kept rows."""
    row = np.full(int(quads.max()) + 1, -1)
    row[kept] = np.arange(len(kept))
    mapped = row[quads]
    whole = mapped[(mapped >= 0).all(axis=1)]
    return np.concatenate([whole[:, [0, 1, 2]], whole[:, [0, 2, 3]]])


def skin_weights(
    table: dict, vertices_mh: np.ndarray, rig: BodyModel, matches: dict, engine: dict
) -> SkinWeights:
    """Return the engine joints' weights: MakeHuman's, each bone's to the joint that
    carries it, but a digit's laid out again along the engine's joints of the digit (by
    each vertex's share of the digit's length), since MakeHuman's finger joints sit
    elsewhere along its shorter fingers."""
    names = rig.skeleton.names
    dense = np.zeros((len(vertices_mh), len(names)))
    digit_share: dict = {}
    for bone, (rows, values) in table.items():
        joint = engine_joint(bone)
        if bone.startswith("finger"):
            digit_share.setdefault((bone[-1], bone[6]), []).append((rows, values))
            continue
        np.add.at(dense, (rows, names.index(joint)), values)
    for (suffix, number), entries in digit_share.items():
        side = "right" if suffix == "R" else "left"
        digit = next(d for d, k in DIGITS.items() if str(k) == number)
        on_digit = np.zeros(len(vertices_mh))
        for rows, values in entries:
            np.add.at(on_digit, rows, values)
        rows = np.flatnonzero(on_digit)
        share = chain_position(vertices_mh[rows], matches[side].chains[digit])
        joints = [f"{side}_{j}" for j in digit_joints(digit)]
        at = chain_shares(np.array([engine[j] for j in joints]))
        # Each joint's weight rises from 0 to 1 across its own position's blend zone.
        previous = np.zeros(len(rows))
        for k, joint in enumerate(joints[:-1]):
            if k + 1 < len(joints) - 1:
                after = np.clip((share - at[k + 1]) / DIGIT_BLEND_SHARE + 0.5, 0.0, 1.0)
            else:
                after = np.zeros(len(rows))
            own = np.clip(1.0 - after - previous, 0.0, 1.0)
            dense[rows, names.index(joint)] += on_digit[rows] * own
            previous = previous + own
    return SkinWeights(*strongest_weights(dense))


def _transforms(skeleton, matches, engine: dict) -> tuple[dict, Affine]:
    """Return each MakeHuman bone's transform onto the engine's skeleton, and the head's."""

    def mean(*names):
        return np.mean([skeleton.head(n) for n in names], axis=0)

    pelvis, shoulders = skeleton.head("spine05"), mean("upperarm01.R", "upperarm01.L")
    eyes = mean("eye.R", "eye.L")
    e_shoulders = (engine["right_shoulder"] + engine["left_shoulder"]) / 2
    e_eyes = (engine["right_eye"] + engine["left_eye"]) / 2
    across = abs(engine["right_shoulder"][0]) / abs(skeleton.head("upperarm01.R")[0])
    head_scale = (e_eyes[1] - e_shoulders[1]) / (eyes[1] - shoulders[1])
    scales = np.array([across, across, head_scale])
    levels = np.array([pelvis, shoulders, eyes])
    targets = np.array([engine["hips"], e_shoulders, e_eyes])
    trunk = TrunkWarp(levels[:, 1], targets[:, 1], scales, targets[:, 2] - scales * levels[:, 2])
    head = Affine(eyes, e_eyes, head_scale * np.eye(3))
    transforms = {}
    for bone in skeleton.names:
        joint = engine_joint(bone)
        if joint in TRUNK_JOINTS or joint.endswith("clavicle"):
            transforms[bone] = trunk
        elif joint == "head" or joint.endswith("_eye"):
            transforms[bone] = head
    for side in SIDES:
        s, p, match = SIDE_SUFFIX[side], side + "_", matches[side]
        arm = match.arm
        for bones, (a, b) in (
            (("upperarm01", "upperarm02"), ("shoulder", "elbow")),
            (("lowerarm01", "lowerarm02"), ("elbow", "wrist")),
        ):
            segment = segment_affine(arm[p + a], arm[p + b], engine[p + a], engine[p + b], across)
            transforms.update({bone + s: segment for bone in bones})
        points = joint_points(match)
        names = [p + n for n in ("wrist", "index_mcp", "pinky_mcp", "middle_mcp")]
        frame_mh = palm_frame(*(points[n] for n in names), side)
        frame_e = palm_frame(*(engine[n] for n in names), side)
        width = np.linalg.norm(engine[names[1]] - engine[names[2]]) / np.linalg.norm(
            points[names[1]] - points[names[2]]
        )
        length = np.linalg.norm(engine[names[3]] - engine[names[0]]) / np.linalg.norm(
            points[names[3]] - points[names[0]]
        )
        palm = frame_affine(
            frame_mh, frame_e, points[names[0]], engine[names[0]], (width, length, width)
        )
        transforms.update(
            {
                bone + s: palm
                for bone in ("wrist", "metacarpal1", "metacarpal2", "metacarpal3", "metacarpal4")
            }
        )
        transforms.update(digit_transforms(match, engine, side, DIGIT_GIRTH))
    return transforms, head


def warp_body(body: str | Phenotype, dominant: str) -> Warped:
    """Return MakeHuman's body in *body*'s shape (a preset or a phenotype) on the engine's
    rig."""
    mesh = assets.base_mesh()
    shaped = shaped_vertices(mesh.vertices_m, body_phenotype(body), assets.macro_target)
    skeleton = place_skeleton(assets.rig_json(), shaped, mesh.group)
    weights = assets.weights_json()
    rig = BodyModel(dominant)
    matches = {side: correspondence(skeleton, shaped, weights, rig, side) for side in SIDES}
    bind = fit_bind_dofs(rig, matches)
    positions = rig.pose(bind).positions_m[0]
    engine = dict(zip(rig.skeleton.names, positions, strict=True))
    transforms, head = _transforms(skeleton, matches, engine)
    body = mesh.group("body")
    kept = body[shaped[body, 1] > skeleton.head("spine05")[1] - CUT_BELOW_PELVIS_M]
    table = bone_weights(weights, kept)
    warped = blend_warp(shaped[kept], table, transforms)
    eyes = np.array(
        [head(sphere_fit(shaped[mesh.group(f"helper-{s}-eye")])[0][None])[0] for s in ("r", "l")]
    )
    helpers = {name: (mesh.group(name), head(shaped[mesh.group(name)])) for name in HELPERS}
    return Warped(
        rig,
        bind,
        warped,
        quad_triangles(mesh.quads, kept),
        kept,
        skin_weights(table, shaped[kept], rig, matches, engine),
        head,
        eyes,
        helpers,
    )
