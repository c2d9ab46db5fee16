"""Test joint-name mapping of third-party skeletons and retargeting onto the models."""

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from synthesis.fingerspelling.alphabet import letter_pose
from synthesis.rigs.body import BodyModel
from synthesis.rigs.face import is_face_dof
from synthesis.rigs.hand import HandModel
from synthesis.rigs.retarget import retarget
from synthesis.skeleton.mapping import JOINT_NAME_TABLES, detect_mapping, normalise
from synthesis.skeleton.motion import Motion
from synthesis.skeleton.rotations import quat_multiply
from synthesis.skeleton.skeleton import Joint, Skeleton


def _renamed(skeleton: Skeleton, names: dict[str, str], prefix: str = "") -> Skeleton:
    return Skeleton(
        tuple(
            Joint(prefix + names.get(j.name, j.name), j.parent, j.offset, j.channels, j.is_end_site)
            for j in skeleton.joints
        ),
        skeleton.length_unit,
    )


@pytest.mark.parametrize(
    "convention, prefix, sample",
    [
        ("humanik", "mixamorig:", "RightHandIndex1"),
        ("xsens", "", "RightSecondMCP"),
        ("blender", "", "f_index.01.R"),
    ],
)
def test_detects_each_convention(convention, prefix, sample):
    skeleton = _renamed(BodyModel().skeleton, JOINT_NAME_TABLES[convention], prefix)
    mapping = detect_mapping(skeleton)
    assert mapping.convention == convention
    assert mapping.to_canonical[prefix + sample] == "right_index_mcp"
    assert not mapping.is_single_hand


def test_names_match_without_case_separators_or_namespace():
    assert normalise("mixamorig:RightHandIndex1") == normalise("right_hand_index_1")
    assert normalise("f_index.01.R") == "findex01r"


def test_a_hand_file_maps_to_the_hand():
    mapping = detect_mapping(HandModel().skeleton)
    assert mapping.is_single_hand and mapping.to_canonical["index_pip"] == "index_pip"


def test_unknown_skeleton_gets_an_error_naming_the_problem():
    skeleton = Skeleton(
        (Joint("Bone0", -1, (0, 0, 0), ("Xrotation",)), Joint("Bone1", 0, (0, 1, 0), ()))
    )
    with pytest.raises(ValueError, match=r"Cannot map this skeleton's joints \(Bone0, Bone1"):
        detect_mapping(skeleton)


def _world_aligned_copy(model, dofs: np.ndarray) -> Motion:
    """Return a Mixamo-named BVH motion of *model*'s poses, built like third-party files:
    identity rest frames, offsets in world axes (cm), rotations relative to that rest."""
    neutral = model.pose(model.neutral())
    rest_q, rest_p = neutral.quaternions[0], neutral.positions_m[0]
    parents = model.skeleton.parents
    names = JOINT_NAME_TABLES["humanik"]
    joints = []
    for i, joint in enumerate(model.skeleton.joints):
        offset = rest_p[i] if parents[i] < 0 else rest_p[i] - rest_p[parents[i]]
        channels = joint.channels
        if parents[i] < 0:
            channels = ("Xposition", "Yposition", "Zposition", *channels)
        joints.append(
            Joint(
                "mixamorig:" + names.get(joint.name, joint.name),
                joint.parent,
                tuple(offset * 100),
                channels,
                joint.is_end_site,
            )
        )
    skeleton = Skeleton(tuple(joints), "cm")
    pose = model.pose(dofs)
    world = quat_multiply(pose.quaternions, rest_q * [-1, -1, -1, 1])
    rows = []
    for f in range(len(dofs)):
        row = []
        for i, joint in enumerate(skeleton.joints):
            if not joint.channels:
                continue
            if parents[i] < 0:
                row += list(pose.positions_m[f, i] * 100)
                local = world[f, i]
            else:
                local = quat_multiply(world[f, parents[i]] * [-1, -1, -1, 1], world[f, i])
            row += list(Rotation.from_quat(local).as_euler("ZXY", degrees=True))
        rows.append(row)
    return Motion(skeleton, np.array(rows), 1 / 60)


# Random poses reach ±90° somewhere; the Euler angles chosen there are still exact.
@pytest.mark.filterwarnings("ignore:Gimbal lock detected")
def test_retargeting_a_renamed_world_aligned_body_reproduces_its_poses():
    """The face's bones are the engine's own (no third-party convention names them), so
    a renamed copy's face stays at rest: the poses here keep it there."""
    model = BodyModel()
    rng = np.random.default_rng(7)
    low, high = model.limits_rad
    body = np.array([not is_face_dof(name) for name in model.dof_names])
    dofs = np.stack(
        [
            model.neutral(),
            model.with_hand(
                model.from_degrees({"right_elbow_flexion": 90, "right_shoulder_flexion": 45}),
                "right",
                letter_pose("R"),
            ),
            rng.uniform(low, high) * 0.4 * body,
        ]
    )
    motion = _world_aligned_copy(model, dofs)
    retargeted = retarget(motion, model)
    assert np.abs(retargeted.positions_m - model.pose(dofs).positions_m).max() < 1e-9


def test_own_skeleton_is_used_as_it_is():
    model = HandModel()
    dofs = letter_pose("F")[None]
    motion = Motion(model.skeleton, model.channel_values(dofs), 1 / 60)
    assert np.allclose(retarget(motion, model).positions_m, model.pose(dofs).positions_m)


def test_an_end_site_after_a_fingers_last_joint_is_its_tip():
    from synthesis.skeleton.bvh import format_bvh, parse_bvh

    model = HandModel()
    motion = Motion(model.skeleton, model.channel_values(model.neutral()[None]), 1 / 30)
    read_back = parse_bvh(format_bvh(motion))
    mapping = detect_mapping(read_back.skeleton)
    assert mapping.to_canonical["index_dip_End"] == "index_tip"
    assert mapping.to_canonical["thumb_ip_End"] == "thumb_tip"
