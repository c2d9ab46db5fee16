"""The stimulus check (synthesis.quality) finds what a viewer would see wrong.

Each check is shown failing on a planted case: a technique that doubles one joint's
speed, a hand pushed into the chest, a camera that loses the hand, a hand over the face,
a clip rendered too small. References: scipy's Rotation for angles; issue 52 for the
hand sizes (fist letters at about 21 × 32 px could not be told apart).
"""

import json
from dataclasses import replace

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from stimuli import ClipSpec, checked, quality_file
from synthesis.identity import code_digest
from synthesis.quality import SPEED_FACTOR, check_request, keyed_reference
from synthesis.quality.contact import BodySurface
from synthesis.quality.speed import joint_speeds_deg_s
from synthesis.quality.visibility import CELL_PX, _hidden_share, measure_visibility
from synthesis.render.scene import CameraPreset
from synthesis.skeleton.kinematics import Pose
from synthesis.techniques import REGISTRY, ClipRequest, Parameter, Technique
from synthesis.techniques.registry import MOTION
from synthesis.techniques.request import avatar_and_camera
from synthesis.techniques.spine import DEFAULTS as SPINE_DEFAULTS

SENTENCE = "BUT SURPRISE MY BROTHER GET NEW"


def _double_the_elbow(build):
    """Plant a fling: the dominant elbow's flexion swings twice as far, so twice as fast."""
    if not build.request.parameters["fling"]:
        return build
    motion = np.array(build.motion, dtype=np.float64)
    column = build.rig.dof_names.index(f"{build.request.side}_elbow_flexion")
    motion[:, column] = 2 * motion[:, column] - motion[0, column]
    return build.but(motion=motion)


FLING = Technique(
    name="fling",
    label="Planted fling",
    kinds=frozenset({"sentence"}),
    parameters=(Parameter("fling", "bool", False, "Double the elbow's speed."),),
    source="a test",
    stage=MOTION,
    apply=_double_the_elbow,
)


def test_joint_speed_is_the_local_rotation_angle_per_second():
    """A child turning 3° a frame about a tilted axis under a parent turning with it."""
    rate_hz, n = 60.0, 20
    axis = np.array([1.0, 2.0, 2.0]) / 3.0
    parent = Rotation.from_rotvec(np.outer(np.radians(np.arange(n) * 5.0), [0, 1, 0]))
    local = Rotation.from_rotvec(np.outer(np.radians(np.arange(n) * 3.0), axis))
    quaternions = np.stack([parent.as_quat(), (parent * local).as_quat()], axis=1)
    pose = Pose(quaternions, np.zeros((n, 2, 3)))
    speeds = joint_speeds_deg_s(pose, np.array([-1, 0]), rate_hz)
    assert speeds[:, 0] == pytest.approx(5.0 * rate_hz)
    assert speeds[:, 1] == pytest.approx(3.0 * rate_hz)


def test_the_keyed_reference_keeps_the_content_and_resets_the_motion_techniques():
    """The spine's on or off is kept (which joints carry the reach), its tuning reset."""
    request = ClipRequest.from_parameters(
        "sentence",
        SENTENCE,
        {"transition": "hermite", "spine": False, "spine_bend_deg": 20.0, "skin_tone": "dark"},
    )
    reference = keyed_reference(request).parameters
    assert reference["transition"] == "keyed" and reference["spine"] is False
    assert reference["spine_bend_deg"] == SPINE_DEFAULTS.bend_deg != 20.0
    assert reference["skin_tone"] == "dark"


@pytest.mark.slow
def test_a_planted_fling_is_caught_and_the_plain_clip_is_not():
    with REGISTRY.registered(FLING):
        plain = check_request(ClipRequest("sentence", SENTENCE, {}, width=1280, height=720))
        flung = check_request(
            ClipRequest("sentence", SENTENCE, {"fling": True}, width=1280, height=720)
        )
    assert plain.ok, plain.findings
    speed = [f for f in flung.findings if f.check == "speed"]
    assert speed and speed[0].message.startswith("right_elbow turns at"), flung.findings
    assert flung.figures["speed_ratio"] == pytest.approx(2.0, abs=0.05)
    assert flung.figures["speed_ratio"] > SPEED_FACTOR


@pytest.mark.slow
def test_the_same_sentence_is_too_small_at_640x480_and_readable_at_720p():
    """Issue 52: the demo's 640×480 sentence clips show fists too small to tell apart."""
    small = check_request(ClipRequest("sentence", SENTENCE, {}))
    assert [f.check for f in small.findings] == ["size"], small.findings
    assert small.figures["hand_px_p5"] < 56 <= small.figures["hand_px_median"]


def _shifted(camera: CameraPreset, offset_m) -> CameraPreset:
    """Return *camera* moved by *offset_m*, looking the same way."""
    return replace(
        camera,
        eye_m=tuple(np.add(camera.eye_m, offset_m)),
        target_m=tuple(np.add(camera.target_m, offset_m)),
    )


def test_a_resting_hand_below_the_frame_is_lowered_and_one_out_at_the_side_is_outside():
    """Issue 52: the 16:9 signing view ends at the waist, so the non-dominant hand hangs
    below the frame while the other signs: lowered, no finding. The same motion filmed
    by the camera moved 0.6 m to the signer's left loses the right hand at the side."""
    request = ClipRequest("sentence", SENTENCE, {}, width=1280, height=720)
    quality = check_request(request)
    assert not [f for f in quality.findings if f.check == "frame"], quality.findings
    assert quality.figures["frames_hand_outside"] == 0
    assert quality.figures["frames_hand_lowered"] > 0

    from synthesis.techniques import build_motion

    build = build_motion(request)
    avatar, camera = avatar_and_camera("upper-body", "right", width=1280, height=720)
    pose = avatar.rig.pose(np.asarray(build.motion))
    view = measure_visibility(avatar, _shifted(camera, (0.6, 0.0, 0.0)), pose, 1280, 720)
    right = view.hands.index("right")
    assert view.outside[:, right].any() and not view.lowered[:, right].all()

    # The close-up's lone hand has no body to rest beside: the camera raised until the
    # hand leaves through the bottom edge loses it (outside), it is not lowered.
    hand, close_up = avatar_and_camera("hand", "right")
    still = hand.rig.pose(hand.rig.neutral()[None])
    seen, lost = (
        measure_visibility(hand, _shifted(close_up, (0.0, lift_m, 0.0)), still, 640, 480)
        for lift_m in (0.0, 0.3)
    )
    assert not seen.outside.any() and not seen.lowered.any()
    assert lost.outside.all() and not lost.lowered.any()


def test_a_point_in_the_chest_is_inside_the_body_and_one_in_front_is_not():
    avatar, _ = avatar_and_camera("upper-body", "right")
    surface = BodySurface.of(avatar)
    bind = avatar.bind_pose
    chest = bind.positions_m[:, [avatar.rig.skeleton.names.index("spine_upper")]]
    assert surface.signed_distance_m(bind, chest)[0, 0] < -0.03
    assert surface.signed_distance_m(bind, chest + np.array([0.0, 0.0, 0.6]))[0, 0] > 0.1
    # The chest's skin pushed 3 cm in along its normal (the face's is not: see
    # synthesis.quality.contact on the eye and mouth openings).
    skin, names = avatar.parts[0], avatar.rig.skeleton.names
    owner = np.array(names)[skin.weights.main_joints()]
    front = np.flatnonzero(
        np.isin(owner, ["spine_upper", "spine_middle"])
        & (skin.normals[:, 2] > 0.9)
        & (np.abs(skin.vertices_m[:, 0]) < 0.12)
    )[::5]
    assert len(front) > 10
    inside = (skin.vertices_m[front] - 0.03 * skin.normals[front])[None]
    assert surface.signed_distance_m(bind, inside)[0] == pytest.approx(-0.03, abs=0.01)


def test_a_hand_over_the_face_hides_it_and_one_beside_it_does_not():
    """Face points at depth 2 m behind a 40 × 40 px square of hand at 1.6 m."""
    grid = np.stack(np.meshgrid(np.arange(100, 140, 1.0), np.arange(100, 140, 1.0)), -1)
    hand = grid.reshape(1, -1, 2)
    face = (grid[::4, ::4].reshape(1, -1, 2)) + 0.5
    beside = face + np.array([60.0, 0.0])
    hidden = _hidden_share(
        hand, np.full(hand.shape[:2], 1.6), face, np.full(face.shape[:2], 2.0), 320, 240
    )
    shown = _hidden_share(
        hand, np.full(hand.shape[:2], 1.6), beside, np.full(face.shape[:2], 2.0), 320, 240
    )
    behind = _hidden_share(
        hand, np.full(hand.shape[:2], 2.4), face, np.full(face.shape[:2], 2.0), 320, 240
    )
    assert hidden[0] == 1.0 and shown[0] == 0.0 and behind[0] == 0.0
    assert CELL_PX <= 4


def test_a_clip_check_is_kept_by_content_hash_and_read_back(tmp_path):
    spec = ClipSpec("word", "AB", {"timing": "constant"}, rate_hz=30)
    first = checked(spec, tmp_path)
    path = quality_file(tmp_path, spec.content_hash())
    assert json.loads(path.read_text()) == {**first.to_dict(), "checked_by": code_digest()}
    kept = {**first.to_dict(), "figures": {"kept": True}, "checked_by": code_digest()}
    path.write_text(json.dumps(kept))
    assert checked(spec, tmp_path).figures == {"kept": True}  # read, not made again
    # A check made by other checking code is made again (the clip's hash leaves it out).
    path.write_text(json.dumps({**kept, "checked_by": "another engine"}))
    assert checked(spec, tmp_path).figures == first.figures
