"""Test third-party motion retargeted onto the engine's body (issue 37): CMU clips from
Debian's assimp-testmodels (/usr/share/assimp/models/BVH, subject 1's 01_01 and 01_03,
CMU Graphics Lab Motion Capture Database), their bones' directions kept; the same
through assimp's converter; the package's FBX read through assimp.

scripts/system-packages.txt installs the package; without it these tests say so and skip.
"""

import shutil
import warnings
from pathlib import Path

import numpy as np
import pytest

from synthesis.avatar.imported.gltf_read import GltfError
from synthesis.avatar.imported.motion import assimp_to_glb, read_gltf_motion, read_motion_file
from synthesis.cli import main
from synthesis.rigs.body import BodyModel
from synthesis.rigs.retarget import bone_direction_errors_deg, retarget
from synthesis.skeleton.bvh import BvhError, BvhWarning, read_bvh
from synthesis.skeleton.kinematics import forward_kinematics
from synthesis.skeleton.mapping import detect_mapping
from synthesis.skeleton.retime import resample
from synthesis.techniques import ClipRequest, build_motion

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


def _angle_deg(positions: np.ndarray, a: int, b: int, c: int) -> np.ndarray:
    """Return the angle (degrees, per frame) between bones a→b and b→c."""
    first, second = positions[:, b] - positions[:, a], positions[:, c] - positions[:, b]
    cosine = np.sum(first * second, axis=1)
    cosine /= np.linalg.norm(first, axis=1) * np.linalg.norm(second, axis=1)
    return np.degrees(np.arccos(np.clip(cosine, -1.0, 1.0)))


@needs_models
def test_a_cmu_hand_bends_at_the_wrist_as_the_capture_does_and_stays_in_place():
    """Issue 54: CMU's hand turns through LeftFingerBase, a second frame on the wrist the
    fingers hang from; mapping LeftHand alone held the engine's wrist at 90° to the
    forearm in every frame (CMU's bends 0–51°), and the root's 0.67 m walk took the body
    out of the fixed camera. Measured: within 3.0° (the knuckles sit off the line CMU's
    finger bone takes), and no travel across the floor in place."""
    motion = resample(read_bvh(MODELS / "BVH" / "01_01.bvh"), 30.0)
    mapping = detect_mapping(motion.skeleton)
    body = BodyModel("right")
    pose = retarget(motion, body, mapping, in_place=True)
    source = forward_kinematics(motion)
    ours, theirs = body.skeleton.index, motion.skeleton.index
    for side, cap in (("left", "L"), ("right", "R")):
        wide = cap.replace("L", "Left").replace("R", "Right")
        joints = [ours(f"{side}_{j}") for j in ("elbow", "wrist", "middle_mcp")]
        bent = _angle_deg(pose.positions_m, *joints)
        captured = [theirs(f"{wide}ForeArm"), theirs(f"{wide}Hand"), theirs(f"{cap}Fingers")]
        assert np.ptp(_angle_deg(source.positions_m, *captured)) > 35.0
        assert np.abs(bent - _angle_deg(source.positions_m, *captured)).max() < 3.5, side
    hips = pose.positions_m[:, ours("hips")]
    assert np.abs(hips[:, [0, 2]] - hips[0, [0, 2]]).max() < 1e-9
    walked = retarget(motion, body, mapping).positions_m[:, ours("hips")]
    assert np.ptp(walked[:, 2]) > 0.5


def _mean_facing_deg(pose, body) -> float:
    """Return the circular mean over frames of the engine's shoulder line's turn (degrees)."""
    index = body.skeleton.index
    line = (
        pose.positions_m[:, index("left_shoulder")] - pose.positions_m[:, index("right_shoulder")]
    )
    turn = np.arctan2(-line[:, 2], line[:, 0])
    return float(np.degrees(np.arctan2(np.sin(turn).mean(), np.cos(turn).mean())))


@needs_models
def test_a_capture_that_faces_away_is_filmed_facing_the_camera():
    """Issue 54: Boxing_Toes's boxer faces away from the camera (172° on average); in
    place, it faces the camera (measured: the engine's shoulders 0.2° on average)."""
    motion = read_bvh(MODELS / "BVH" / "Boxing_Toes.bvh")
    mapping = detect_mapping(motion.skeleton)
    # Biovision's names: 13 joints with the spine and collars (9 before, no spine).
    assert mapping.convention == "biovision" and len(mapping.to_canonical) == 13
    assert {"Ab", "Chest", "LeftCollar"} <= set(mapping.to_canonical)
    body = BodyModel("right")
    assert abs(_mean_facing_deg(retarget(motion, body, mapping), body)) > 150
    assert abs(_mean_facing_deg(retarget(motion, body, mapping, in_place=True), body)) < 2


@needs_models
def test_a_bvh_with_a_line_past_its_frame_count_reads_as_assimp_reads_it(tmp_path):
    # Boxing_Toes.bvh says "Frames: 3069" above 3070 frame lines; assimp (and Blender,
    # bvhio) read it: assimp gives 3069 keys, the declared count (issue 54, item 5).
    source = MODELS / "BVH" / "Boxing_Toes.bvh"
    with pytest.warns(BvhWarning, match="'Frames: 3069' above 3070 frame lines; the last 1"):
        motion = read_bvh(source)
    assert motion.n_frames == 3069
    # One frame line short of the count is a file cut short: refused, naming it.
    lines = source.read_text().splitlines()
    cut = tmp_path / "cut.bvh"
    cut.write_text("\n".join(lines[: len(lines) - 2]) + "\n")
    with pytest.raises(BvhError, match="'Frames: 3069' but the file has 3068 frame lines"):
        read_bvh(cut)


needs_assimp = pytest.mark.skipif(
    shutil.which("assimp") is None,
    reason="Debian's assimp-utils is not installed (scripts/system-packages.txt)",
)


@needs_models
@needs_assimp
def test_motion_through_assimp_retargets_as_the_bvh_itself():
    # assimp reads the CMU BVH and writes glTF; read back as motion, the body moves as
    # when the BVH is read directly.
    source = MODELS / "BVH" / "01_01.bvh"
    direct = resample(read_bvh(source), 30.0)
    converted = read_gltf_motion(assimp_to_glb(source), "01_01.glb", 30.0)
    body = BodyModel("right")
    a, b = retarget(direct, body), retarget(converted, body)
    n = min(direct.n_frames, converted.n_frames)
    names = body.skeleton.names
    for joint, child in (
        ("right_elbow", "right_wrist"),
        ("left_shoulder", "left_elbow"),
        ("spine_middle", "spine_upper"),
    ):
        ours = a.positions_m[:n, names.index(child)] - a.positions_m[:n, names.index(joint)]
        theirs = b.positions_m[:n, names.index(child)] - b.positions_m[:n, names.index(joint)]
        cosine = (
            np.sum(ours * theirs, axis=1)
            / np.linalg.norm(ours, axis=1)
            / np.linalg.norm(theirs, axis=1)
        )
        assert np.degrees(np.arccos(np.clip(cosine, -1, 1))).max() < 0.05, joint


@needs_models
@needs_assimp
def test_an_fbx_goes_in_through_assimp_and_a_skeleton_that_is_no_humanoid_is_named():
    motion = read_motion_file(MODELS / "FBX" / "animation_with_skeleton.fbx")
    assert motion.n_frames == 21 and motion.rate_hz == pytest.approx(24.0)
    assert {"Bone", "Bone.001", "Bone.013"} <= set(motion.skeleton.names)
    with pytest.raises(ValueError, match=r"Cannot map this skeleton's joints \(.*Bone"):
        detect_mapping(motion.skeleton)
    with pytest.raises(GltfError, match="assimp cannot read"):
        read_motion_file(MODELS / "FBX" / "transparentTest.fbx")  # no animation: none to read


@needs_models
def test_the_mapping_says_which_parts_stay_at_rest():
    """Issue 54 (6): a partial mapping used to pass in silence. CMU's clips have no
    fingers; the engine's own motion maps every part."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", BvhWarning)
        cmu = detect_mapping(read_bvh(MODELS / "BVH" / "01_01.bvh").skeleton)
    assert cmu.unmapped_parts() == ["left hand's fingers", "right hand's fingers"]
    build = build_motion(ClipRequest.from_parameters("sentence", "ME", {"rate_hz": 15.0}))
    ours = build.rig.as_motion(build.motion, 15.0)
    assert detect_mapping(ours.skeleton).unmapped_parts() == []


TRUNK_ONLY = (
    """HIERARCHY
ROOT Hips
{
  OFFSET 0 0 0
  CHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation
  JOINT LowerBack
  {
    OFFSET 0 2 0
    CHANNELS 3 Zrotation Xrotation Yrotation
    JOINT Spine
    {
      OFFSET 0 2 0
      CHANNELS 3 Zrotation Xrotation Yrotation
      JOINT Neck
      {
        OFFSET 0 2 0
        CHANNELS 3 Zrotation Xrotation Yrotation
        JOINT Head
        {
          OFFSET 0 2 0
          CHANNELS 3 Zrotation Xrotation Yrotation
          End Site
          {
            OFFSET 0 2 0
          }
        }
      }
    }
  }
}
MOTION
Frames: 2
Frame Time: 0.033333
"""
    + "0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0\n" * 2
)


def test_a_motion_without_arms_is_refused_by_name(tmp_path, capsys):
    path = tmp_path / "trunk.bvh"
    path.write_text(TRUNK_ONLY)
    assert main(["render-bvh", str(path), "--out", str(tmp_path / "trunk.mp4")]) == 2
    assert "trunk.bvh: no arm joint is mapped" in capsys.readouterr().err


@needs_models
def test_render_bvh_films_a_capture_in_place_unless_asked_to_keep_it_as_captured(
    tmp_path, renderable, capsys
):
    """Issue 54 (2, 5): facing and travel are normalised by default, an option keeps them."""
    source = MODELS / "BVH" / "01_01.bvh"
    for option, out in (([], "in-place.mp4"), (["--as-captured"], "as-captured.mp4")):
        arguments = [str(source), "--rate", "4", "--size", "64x48", "--out", str(tmp_path / out)]
        assert main(["render-bvh", *arguments, *option]) == 0
    assert (tmp_path / "in-place.mp4").stat().st_size > 0
    assert (tmp_path / "as-captured.mp4").stat().st_size > 0
    assert "not mapped, so at rest: left hand's fingers" in capsys.readouterr().err
