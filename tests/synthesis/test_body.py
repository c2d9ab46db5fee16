"""Test the upper-body model: joints of seed 003 §3.2, DOF directions, mirroring, hands."""

import numpy as np

from synthesis.fingerspelling.alphabet import letter_pose
from synthesis.rigs.body import BodyModel
from synthesis.rigs.hand import HandModel
from synthesis.rigs.posture import fingerspelling_posture


def _at(model, dofs, joint):
    return model.pose(dofs).positions_m[0, model.skeleton.index(joint)]


def test_has_the_joints_of_seed_003():
    names = BodyModel().skeleton.names
    for joint in ("hips", "spine_lower", "spine_middle", "spine_upper", "neck", "head"):
        assert joint in names
    for side in ("right", "left"):
        for joint in ("clavicle", "shoulder", "elbow", "forearm", "wrist", "index_tip"):
            assert f"{side}_{joint}" in names
    dofs = BodyModel().dof_names
    assert {"right_clavicle_raise", "right_clavicle_forward"} <= set(dofs)  # 2-DOF clavicle
    assert "riIndexMCPy" in BodyModel().literature_names


def test_dofs_move_the_way_their_names_say():
    model = BodyModel()
    rest = model.neutral()
    assert _at(model, rest, "right_wrist")[0] < 0  # the signer's right is the viewer's left
    forward = model.from_degrees({"right_shoulder_flexion": 90})
    assert _at(model, forward, "right_wrist")[2] > 0.4
    out = model.from_degrees({"right_shoulder_abduction": 90})
    assert _at(model, out, "right_wrist")[0] < -0.6
    elbow = model.from_degrees({"right_elbow_flexion": 90})
    assert _at(model, elbow, "right_wrist")[2] > 0.2
    raised = model.from_degrees({"right_clavicle_raise": 20})
    assert _at(model, raised, "right_shoulder")[1] > _at(model, rest, "right_shoulder")[1]
    bow = model.from_degrees({"spine_middle_flexion": 20})
    assert _at(model, bow, "head")[2] > 0.05
    turn = model.from_degrees({"spine_upper_rotation": 20})
    # Turning toward the signer's left brings the right shoulder forward.
    assert _at(model, turn, "right_shoulder")[2] > _at(model, rest, "right_shoulder")[2]


def test_left_side_mirrors_the_right():
    model = BodyModel()
    right = model.from_degrees(
        {"right_shoulder_flexion": 40, "right_elbow_flexion": 70, "right_index_mcp_flexion": 50}
    )
    left = model.from_degrees(
        {"left_shoulder_flexion": 40, "left_elbow_flexion": 70, "left_index_mcp_flexion": 50}
    )
    for joint in ("wrist", "index_tip", "thumb_tip"):
        r, l_ = _at(model, right, f"right_{joint}"), _at(model, left, f"left_{joint}")
        assert np.allclose(r * [-1, 1, 1], l_, atol=1e-12)


def test_a_letter_keeps_its_handshape_on_the_body():
    """The hand's joints relative to its wrist match the hand model's, up to rotation."""
    body, hand = BodyModel(), HandModel()
    shape = letter_pose("W")
    dofs = fingerspelling_posture(body, "right", shape[None])[0]
    on_body = body.pose(dofs).positions_m[0]
    alone = hand.pose(shape).positions_m[0]
    names = [n for n in hand.skeleton.names if n != "forearm"]
    a = np.array([alone[hand.skeleton.index(n)] for n in names])
    b = np.array([on_body[body.skeleton.index("right_" + n)] for n in names])
    a, b = a - a.mean(axis=0), b - b.mean(axis=0)
    assert np.allclose(
        np.linalg.svd(a, compute_uv=False), np.linalg.svd(b, compute_uv=False), atol=1e-9
    )
    wrist = on_body[body.skeleton.index("right_wrist")]
    assert wrist[1] > 1.2 and wrist[2] > 0.1  # held up in front of the chest


def test_every_letter_is_held_up_in_the_fingerspelling_space_by_the_wrist():
    """Issue 52: P and Q leaned the forearm about a low elbow and hung at the hip (wrist
    27 and 31 cm below B's), G and H dropped to the breastbone (11 cm). The wrist now
    stays within 4 cm of its spelling height whatever the letter turns the hand to, and
    the hand keeps its orientation (the arm lifts, the wrist turns down)."""
    from synthesis.rigs.posture import MAX_WRIST_DROP_M

    body = BodyModel()
    wrist = body.skeleton.index("right_wrist")
    spelled = {k: fingerspelling_posture(body, "right", letter_pose(k)[None])[0] for k in "GHPQ"}
    # The spelling height: the wrist with the forearm upright in the hand model (B was the
    # reference while it stood upright; its palm now turns as human B's does).
    upright = fingerspelling_posture(body, "right", HandModel("right").neutral()[None])[0]
    spelling_m = body.pose(upright).positions_m[0, wrist, 1]
    height = {k: body.pose(d).positions_m[0, wrist, 1] for k, d in spelled.items()}
    for k in "GHPQ":
        assert height[k] >= spelling_m - MAX_WRIST_DROP_M - 0.005, (k, height[k], spelling_m)
    # P's middle finger still points down (the wrist turned, not the hand straightened).
    pose = body.pose(spelled["P"]).positions_m[0]
    down = (
        pose[body.skeleton.index("right_middle_tip")]
        - pose[body.skeleton.index("right_middle_mcp")]
    )
    assert down[1] < -0.5 * np.linalg.norm(down)
