"""The human signer's hand and forearm for the close-up, cut from the human body avatar.

The hand model's joints below its forearm are the body's arm joints under another name,
with the same local frames (:mod:`synthesis.rigs.body`), so the body avatar's hand and
forearm skin, nails and sleeve move onto the hand model by one rigid transform: the
body's forearm frame at its bind pose onto the hand model's at the same hand DOFs.
The upper arm's skin near the elbow comes along, on the forearm, so that the cut is out
of the close-up's frame.
"""

from functools import cache

import numpy as np

from synthesis.avatar.human.build import DEFAULT_SKIN_TONE, LIBRARIES, SKIN_TONES, human_avatar
from synthesis.avatar.human.features import nail_radii
from synthesis.avatar.human.phenotype import DEFAULT_PRESET, Phenotype, body_key
from synthesis.avatar.model import NAIL_RGB, Avatar, SkinnedPart, rigid_part
from synthesis.avatar.skinning import SkinWeights
from synthesis.rigs.hand import HandModel
from synthesis.skeleton.rotations import quat_to_matrix

# Upper-arm skin kept above the elbow (m), carried by the forearm.
ABOVE_ELBOW_M = 0.06


def _frame(pose, index: int) -> np.ndarray:
    """Return a joint's world transform (4, 4) in a one-frame pose."""
    transform = np.eye(4)
    transform[:3, :3] = quat_to_matrix(pose.quaternions[0, index])
    transform[:3, 3] = pose.positions_m[0, index]
    return transform


def _hand_part(body: Avatar, side: str, model: HandModel, move: np.ndarray) -> SkinnedPart:
    """Return the body skin's hand, forearm and elbow, moved by *move* (4, 4) and
    weighted to the hand model's joints."""
    skin = body.parts[0]
    names = body.rig.skeleton.names
    p = side + "_"
    to_hand = {
        names.index(p + n): model.skeleton.index(n) for n in model.skeleton.names if p + n in names
    }
    to_hand[names.index(p + "elbow")] = model.skeleton.index("forearm")
    to_hand[names.index(p + "shoulder")] = model.skeleton.index("forearm")
    top = skin.weights.main_joints()
    bind = body.bind_pose.positions_m[0]
    elbow, shoulder = bind[names.index(p + "elbow")], bind[names.index(p + "shoulder")]
    up = (shoulder - elbow) / np.linalg.norm(shoulder - elbow)
    near_elbow = (skin.vertices_m - elbow) @ up < ABOVE_ELBOW_M
    kept = np.isin(top, list(to_hand)) & near_elbow
    kept &= ~((top == names.index(p + "shoulder")) & ~near_elbow)
    row = np.full(len(kept), -1)
    row[kept] = np.arange(kept.sum())
    faces = row[skin.faces]
    faces = faces[(faces >= 0).all(axis=1)]
    joints = skin.weights.joints[kept]
    weights = np.where(np.isin(joints, list(to_hand)), skin.weights.weights[kept], 0.0)
    joints = np.vectorize(lambda j: to_hand.get(int(j), 0))(joints)
    weights /= weights.sum(axis=1, keepdims=True)
    turn = move[:3, :3]
    return SkinnedPart(
        "skin",
        skin.vertices_m[kept] @ turn.T + move[:3, 3],
        faces,
        skin.colors_rgb[kept],
        SkinWeights(joints.astype(np.intp), weights),
        skin.normals[kept] @ turn.T,
        None if skin.edge_m is None else skin.edge_m[kept],
        None if skin.across_rgb is None else skin.across_rgb[kept],
    )


def build_human_hand(side: str, body_shape: str | Phenotype, skin_tone: str) -> Avatar:
    """Build the human hand-and-forearm avatar from the human body avatar."""
    from synthesis.avatar.hand_mesh import hand_nails

    body = human_avatar("right", body_shape, skin_tone)
    model = HandModel(side)
    bind = np.zeros(len(model.dofs))
    where = body.rig.hand_dofs(side)
    bind[where >= 0] = body.bind_dofs_rad[where[where >= 0]]
    move = _frame(model.pose(bind), model.skeleton.index("forearm")) @ np.linalg.inv(
        _frame(body.bind_pose, body.rig.skeleton.index(f"{side}_forearm"))
    )
    skin = _hand_part(body, side, model, move)
    radii = nail_radii(body.rig, body.bind_dofs_rad, body.parts[0], side)
    nails = rigid_part(
        "nails", *hand_nails(model, bind, side, "", radii), NAIL_RGB, casts_shadow=False
    )
    return Avatar(f"human-hand-{side}", model, bind, (skin, nails))


@cache
def human_hand_avatar(
    side: str = "right", body: str | Phenotype = DEFAULT_PRESET, skin_tone: str = DEFAULT_SKIN_TONE
) -> Avatar:
    """Return the human hand-and-forearm avatar of the close-up (kept on disk as
    :func:`~synthesis.avatar.human.build.human_avatar` is)."""
    from synthesis.avatar.store import cached_avatar

    if skin_tone not in SKIN_TONES:
        human_avatar("right", body, skin_tone)  # names the unknown one
    key = f"human-hand-{side}-{body_key(body)}-{skin_tone}"
    return cached_avatar(
        key, HandModel(side), lambda: build_human_hand(side, body, skin_tone), LIBRARIES
    )
