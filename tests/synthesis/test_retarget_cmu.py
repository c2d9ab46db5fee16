"""Test third-party BVH retargeted onto the engine's body (issue 37): CMU clips from
Debian's assimp-testmodels (/usr/share/assimp/models/BVH, subject 1's 01_01 and 01_03,
CMU Graphics Lab Motion Capture Database), their bones' directions kept.

scripts/system-packages.txt installs the package; without it these tests say so and skip.
"""

from pathlib import Path

import numpy as np
import pytest

from synthesis.rigs.body import BodyModel
from synthesis.rigs.retarget import bone_direction_errors_deg, retarget
from synthesis.skeleton.bvh import BvhError, read_bvh
from synthesis.skeleton.mapping import detect_mapping
from synthesis.skeleton.retime import resample

MODELS = Path("/usr/share/assimp/models")
needs_models = pytest.mark.skipif(
    not (MODELS / "BVH" / "01_01.bvh").is_file(),
    reason="Debian's assimp-testmodels is not installed (scripts/system-packages.txt)",
)


@needs_models
@pytest.mark.parametrize("clip", ["01_01", "01_03"])
def test_a_cmu_clip_keeps_its_bone_directions_on_the_engines_body(clip):
    motion = resample(read_bvh(MODELS / "BVH" / f"{clip}.bvh"), 30.0)
    mapping = detect_mapping(motion.skeleton)
    assert mapping.convention == "cmu"  # HumanIK's arms, a spine and neck of its own
    body = BodyModel("right")
    errors = bone_direction_errors_deg(motion, retarget(motion, body, mapping), body, mapping)
    # Both arms, clavicle to wrist, the spine and the head (legs: the model has none).
    assert {"RightArm→RightForeArm", "LeftForeArm→LeftHand", "Neck1→Head"} <= set(errors)
    mean_deg = float(np.concatenate(list(errors.values())).mean())
    assert mean_deg < 10.0, f"mean bone-direction error {mean_deg:.2f}°"
    for bone in ("RightArm→RightForeArm", "RightForeArm→RightHand", "LeftArm→LeftForeArm"):
        assert errors[bone].max() < 0.5, bone


@needs_models
def test_a_bvh_whose_frame_count_is_wrong_is_refused_naming_it():
    # Boxing_Toes.bvh says "Frames: 3069" above 3070 frame lines.
    with pytest.raises(BvhError, match="'Frames: 3069' but the file has 3070 frame lines"):
        read_bvh(MODELS / "BVH" / "Boxing_Toes.bvh")
