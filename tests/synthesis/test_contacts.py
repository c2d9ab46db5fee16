"""Signs touch the human signer's body where they should, and never go inside it (issue 36).

The sign library's locations were set on the simple avatar; on the human one, ME's
index finger went 13 cm into the chest (9 cm on the simple one), its nail showing
through the top. A fingertip counts as inside when it lies, seen from the camera,
over the trunk or head and between their back and front surfaces.
"""

import numpy as np
import pytest
from scipy.spatial import cKDTree

from synthesis.avatar.looks import Look, avatar_for
from synthesis.signing.signs import default_library
from synthesis.techniques import ClipRequest, build_motion

DIGITS = ("thumb", "index", "middle", "ring", "pinky")
# A fingertip joint lies on the bone's axis, about 7 mm under the skin of the pad: a
# touch puts it up to that far behind the surface it touches.
TOUCH_MM = 7.0
NEAR_M = 0.015


def _owners(avatar) -> np.ndarray:
    """Return the joint that moves each skin vertex most, by name."""
    return np.asarray(avatar.rig.skeleton.names)[avatar.parts[0].weights.main_joints()]


def deepest_inside_mm(avatar, motion: np.ndarray) -> float:
    """Return how far (mm) the deepest fingertip is behind the surface of the trunk or
    head it lies over, inside it (0 when none is)."""
    names = avatar.rig.skeleton.names
    owner = _owners(avatar)
    on_trunk = ~(np.char.startswith(owner, "right_") | np.char.startswith(owner, "left_"))
    tips = [names.index(f"{side}_{digit}_tip") for side in ("right", "left") for digit in DIGITS]
    surface = avatar.deform(motion)[0][0][:, on_trunk]
    points = avatar.rig.pose(motion).positions_m[:, tips]
    deepest = 0.0
    for vertices, frame in zip(surface, points, strict=True):
        for tip in frame:
            near = np.all(np.abs(vertices[:, :2] - tip[:2]) < NEAR_M, axis=1)
            if near.any() and vertices[near, 2].min() < tip[2] < vertices[near, 2].max():
                deepest = max(deepest, 1000 * (vertices[near, 2].max() - tip[2]))
    return deepest


@pytest.fixture(scope="module")
def human():
    return avatar_for("upper-body", "right", Look())


# Both readings of seed 003's spine: the printed bend leans the torso 10–15° toward the
# hands, and a hand placed on the body (the library's ``body:``) goes with it.
FORMULAS = ("comfort", "seed")


@pytest.mark.parametrize("formula", FORMULAS)
@pytest.mark.parametrize("gloss", sorted(default_library().signs))
def test_no_sign_puts_a_fingertip_inside_the_human_signer(human, gloss, formula):
    values = {"rate_hz": 30.0, "spine_formula": formula}
    request = ClipRequest.from_parameters("sentence", gloss, values)
    motion = np.asarray(build_motion(request).motion)
    assert deepest_inside_mm(human, motion) <= TOUCH_MM


# Signs whose dominant hand touches the body, and where (BROTHER's thumb at the
# forehead stopped 98 mm away before its index was raised: the arm could not reach).
TOUCHING = {
    "ME": "trunk",
    "I": "trunk",
    "MY": "trunk",
    "FAVORITE": "head",
    "REMEMBER": "head",
    "INFORM-YOU": "head",
    "BROTHER": "head",
    "HAPPY": "trunk",
    "HAVE": "trunk",
}
# Between the skins of hand and body at the closest; measured 1–11 mm.
TOUCH_GAP_MM = 12.0


def closest_mm(avatar, motion: np.ndarray, where: str) -> float:
    """Return the least distance (mm) over *motion* between the dominant hand's skin and
    the trunk's (spine joints) or the head's (head, neck, jaw, lips)."""
    owner = _owners(avatar)
    arm = ("shoulder", "clavicle", "elbow", "upper", "fore")
    hand = np.array([n.startswith("right_") and not any(a in n for a in arm) for n in owner])
    if where == "trunk":
        body = np.char.startswith(owner, "spine")
    else:
        body = np.isin(owner, ["head", "neck", "jaw", "upper_lip", "lower_lip"])
    frames = avatar.deform(motion)[0][0]
    return 1000 * min(cKDTree(vertices[hand]).query(vertices[body])[0].min() for vertices in frames)


@pytest.mark.parametrize("formula", FORMULAS)
@pytest.mark.parametrize("gloss", sorted(TOUCHING))
def test_a_sign_that_touches_the_body_touches_the_human_signers(human, gloss, formula):
    values = {"rate_hz": 30.0, "spine_formula": formula}
    request = ClipRequest.from_parameters("sentence", gloss, values)
    motion = np.asarray(build_motion(request).motion)
    assert closest_mm(human, motion, TOUCHING[gloss]) <= TOUCH_GAP_MM
