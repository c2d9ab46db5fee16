"""No sign puts a fingertip inside the human signer's body (issue 36).

The sign library's locations were set on the simple avatar; on the human one, ME's
index finger went 13 cm into the chest (9 cm on the simple one), its nail showing
through the top. A fingertip counts as inside when it lies, seen from the camera,
over the trunk or head and between their back and front surfaces.
"""

import numpy as np
import pytest

from synthesis.avatar.looks import Look, avatar_for
from synthesis.signing.signs import default_library
from synthesis.techniques import ClipRequest, build_motion

DIGITS = ("thumb", "index", "middle", "ring", "pinky")
# A fingertip joint lies on the bone's axis, about 7 mm under the skin of the pad: a
# touch puts it up to that far behind the surface it touches.
TOUCH_MM = 7.0
NEAR_M = 0.015


def deepest_inside_mm(avatar, motion: np.ndarray) -> float:
    """Return how far (mm) the deepest fingertip is behind the surface of the trunk or
    head it lies over, inside it (0 when none is)."""
    names = avatar.rig.skeleton.names
    skin = avatar.parts[0]
    sided = [i for i, name in enumerate(names) if name.startswith(("right_", "left_"))]
    owner = skin.weights.joints[np.arange(len(skin.weights.joints)),
                                np.argmax(skin.weights.weights, axis=1)]  # fmt: skip
    on_trunk = ~np.isin(owner, sided)
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


@pytest.mark.parametrize("gloss", sorted(default_library().signs))
def test_no_sign_puts_a_fingertip_inside_the_human_signer(human, gloss):
    request = ClipRequest.from_parameters("sentence", gloss, {"rate_hz": 30.0})
    motion = np.asarray(build_motion(request).motion)
    assert deepest_inside_mm(human, motion) <= TOUCH_MM
