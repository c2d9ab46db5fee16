"""Test the hand model: literature names (seed 002 §3), limits, mirroring, kinematics."""

import numpy as np
import pytest

from synthesis import forward_kinematics
from synthesis.rigs.hand import HandModel
from synthesis.skeleton.motion import Motion


def test_25_digit_curves_per_hand_named_as_in_seed_002():
    names = HandModel("right").literature_names
    digits = [n for n in names if not n.startswith(("riForearm", "riWrist"))]
    assert len(digits) == 25  # seed 002 §3: "25 rotation curves for each hand"
    for name in ("riIndexMCPy", "riPinkyMCPx", "riRingDIPy", "riThumbCMCz", "riThumbIPz"):
        assert name in names
    assert "lePinkyMCPx" in HandModel("left").literature_names


def test_named_dofs_move_what_they_say():
    model = HandModel()
    base = model.pose(model.neutral()).positions_m[0]
    index_tip = model.skeleton.index("index_tip")
    flexed = model.pose(model.from_degrees({"riIndexMCPy": 60})).positions_m[0]
    assert flexed[index_tip, 2] - base[index_tip, 2] > 0.05  # curls toward the palm (+z)
    spread = model.pose(model.from_degrees({"index_mcp_abduction": 20})).positions_m[0]
    assert spread[index_tip, 0] > base[index_tip, 0]  # toward the thumb (+x)


def test_limits_are_enforced_by_clip():
    model = HandModel()
    wild = np.full(len(model.dofs), np.radians(500.0))
    low, high = model.limits_rad
    assert np.all(model.clip(wild) <= high) and np.all(model.clip(-wild) >= low)
    with pytest.raises(KeyError, match="Unknown hand DOF 'riIndexMCPq'"):
        model.from_degrees({"riIndexMCPq": 10})


def test_left_hand_mirrors_the_right():
    right, left = HandModel("right"), HandModel("left")
    pose = right.from_degrees(
        {"index_mcp_flexion": 40, "thumb_cmc_flexion": 30, "wrist_deviation": 10}
    )
    right_points = right.pose(pose).positions_m[0]
    left_points = left.pose(pose).positions_m[0]
    assert np.allclose(left_points * [-1, 1, 1], right_points, atol=1e-12)


def test_channel_values_reproduce_the_pose_through_generic_fk():
    model = HandModel()
    rng = np.random.default_rng(5)
    low, high = model.limits_rad
    dofs = rng.uniform(low, high, (4, len(model.dofs)))
    motion = Motion(model.skeleton, model.channel_values(dofs), 1 / 60)
    assert np.allclose(
        forward_kinematics(motion).positions_m, model.pose(dofs).positions_m, atol=1e-9
    )


def test_fingers_do_not_shrink():
    model = HandModel()
    lengths = []
    for dofs in (
        model.neutral(),
        model.from_degrees({"middle_mcp_flexion": 90, "middle_pip_flexion": 100}),
    ):
        p = model.pose(dofs).positions_m[0]
        joints = [
            model.skeleton.index(n)
            for n in ("middle_mcp", "middle_pip", "middle_dip", "middle_tip")
        ]
        lengths.append(np.linalg.norm(np.diff(p[joints], axis=0), axis=1))
    assert np.allclose(lengths[0], lengths[1])
