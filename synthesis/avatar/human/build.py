"""The human signer: MakeHuman's CC0 body on the engine's upper-body rig.

Built from the installed files (:mod:`synthesis.avatar.human.assets`) with no PyTorch:
the base mesh shaped by a body preset and put on the engine's skeleton
(:mod:`~synthesis.avatar.human.body`), dressed in a long-sleeved top, given eyes, brows,
lashes, a close-cropped hair cap, teeth, tongue and nails and the ARKit blendshapes the
face channels drive (:mod:`~.features`, :mod:`~.face`). Built once per engine version
and look, then loaded from the engine's disk cache (:mod:`synthesis.avatar.store`).
"""

from dataclasses import replace
from functools import cache
from types import MappingProxyType

import numpy as np

from synthesis.avatar.body_mesh import clothing_colours
from synthesis.avatar.human.body import TRUNK_JOINTS, warp_body
from synthesis.avatar.human.face import morph_drive
from synthesis.avatar.human.features import eyes, face_morphs, features, nails
from synthesis.avatar.human.parts import draped, smoothed
from synthesis.avatar.human.phenotype import DEFAULT_PRESET, Phenotype, body_key, body_phenotype
from synthesis.avatar.model import Avatar, SkinnedPart, merge_parts
from synthesis.rigs.body import SIDES, BodyModel

# Skin tones, and for each a top that stands apart from the hands (spec 01: plain
# clothing that contrasts with the skin).
SKIN_TONES = MappingProxyType(
    {
        "light": ((0.86, 0.66, 0.55), (0.11, 0.12, 0.15)),
        "medium": ((0.70, 0.50, 0.38), (0.11, 0.12, 0.15)),
        "dark": ((0.36, 0.23, 0.16), (0.62, 0.66, 0.70)),
    }
)
DEFAULT_SKIN_TONE = "medium"
LIBRARIES = ("numpy", "scipy", "trimesh", "anny")
# Trousers from a waist this far above the hip joint (m), below the frame of the 16:9 view.
TROUSERS_RGB, WAIST_ABOVE_HIPS_M = (0.14, 0.15, 0.19), 0.04
# The top's cloth is smoothed this far inside its neckline and cuffs (m).
TOP_EDGE_M = 0.02
# Beyond that the cloth drapes over details, fully this much farther in (m).
DRAPE_BLEND_M = 0.03


def waistband(rig: BodyModel, bind_pose, warped, colours: np.ndarray, edge: np.ndarray):
    """Return the skin's colours and edge with trousers below the waist: the trunk's
    vertices near the waist show the trousers' colour on the positive side of an edge at
    the waist's height (the top's colour is on the negative side), so that the waistband
    runs straight through the triangles."""
    names = rig.skeleton.names
    waist = bind_pose.positions_m[0, names.index("hips"), 1] + WAIST_ABOVE_HIPS_M
    lower_trunk = np.isin(
        warped.weights.joints[:, 0], [names.index(n) for n in ("hips", "spine_lower")]
    )
    near = lower_trunk & (warped.skin_vertices[:, 1] < waist + 0.1)
    colours = np.where(near[:, None], TROUSERS_RGB, colours)
    edge = np.where(near, waist - warped.skin_vertices[:, 1], edge)
    return colours, edge


def build_human(dominant: str, body: str | Phenotype, skin_tone: str) -> Avatar:
    """Build the human avatar (seconds; :func:`human_avatar` keeps it on disk)."""
    warped = warp_body(body, dominant)
    skin_rgb, top_rgb = SKIN_TONES[skin_tone]
    rig = warped.rig
    bind_pose = rig.pose(warped.bind_dofs_rad)
    head_joint = rig.skeleton.names.index("head")
    # The eyes turn about their centres: the rig's eye joints move there.
    head_position = bind_pose.positions_m[0, head_joint]
    rig = replace(rig, eye_centre_m=tuple(float(v) for v in warped.eyes_m[0] - head_position))
    colours, edge, across = clothing_colours(
        rig, warped.skin_vertices, warped.weights, warped.bind_dofs_rad, skin_rgb, top_rgb
    )
    colours, edge = waistband(rig, bind_pose, warped, colours, edge)
    # Under the top the trunk is cloth: smoothed, well away from its edges.
    names = rig.skeleton.names
    trunk = [names.index(n) for n in TRUNK_JOINTS] + [names.index(f"{s}_clavicle") for s in SIDES]
    on_trunk = warped.weights.joints[:, 0][:, None] == np.array(trunk)
    vertices = smoothed(
        warped.skin_vertices, warped.skin_faces, on_trunk.any(axis=1) & (edge < -TOP_EDGE_M)
    )
    # ... and draped, the trousers too: no anatomy through the cloth (issue 52), blended in
    # from the neckline, cuffs and waistband.
    drape = np.clip((np.abs(edge) - TOP_EDGE_M) / DRAPE_BLEND_M, 0.0, 1.0) * on_trunk.any(axis=1)
    vertices = draped(vertices, warped.skin_faces, drape)
    scale = warped.head.linear[0, 0]
    morphs = face_morphs(warped.kept, vertices, warped.skin_faces, scale)
    skin = SkinnedPart(
        "skin",
        vertices,
        warped.skin_faces,
        colours,
        warped.weights,
        edge_m=edge,
        across_rgb=across,
        morphs=morphs,
    )
    # Two parts, two draw calls a pass: eyes, brows, hair, lashes, teeth and nails cast
    # no shadow of their own (the skin under them does) and are drawn at once.
    detail = merge_parts(
        "features",
        [eyes(warped), features(warped, skin, head_joint), nails(rig, warped.bind_dofs_rad, skin)],
        casts_shadow=False,
    )
    parts = (skin, detail)
    return Avatar(f"human-{dominant}", rig, warped.bind_dofs_rad, parts, morph_drive(rig.dof_names))


@cache
def human_avatar(
    dominant: str = "right",
    body: str | Phenotype = DEFAULT_PRESET,
    skin_tone: str = DEFAULT_SKIN_TONE,
) -> Avatar:
    """Return the human upper-body avatar of *body* (a preset's name or a phenotype),
    built once per engine version and look, then kept on disk by
    :mod:`synthesis.avatar.store`, and once per process in memory."""
    from synthesis.avatar.store import cached_avatar

    body_phenotype(body)  # names an unknown body
    if skin_tone not in SKIN_TONES:
        raise ValueError(f"Unknown skin tone {skin_tone!r}: {', '.join(SKIN_TONES)}.")
    key = f"human-{dominant}-{body_key(body)}-{skin_tone}"
    return cached_avatar(
        key, BodyModel(dominant), lambda: build_human(dominant, body, skin_tone), LIBRARIES
    )
