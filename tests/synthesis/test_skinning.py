"""Test linear blend skinning: weights, bind-pose identity, rigid motion, the formula."""

import numpy as np
from scipy.spatial.transform import Rotation

from synthesis.avatar.sdf import RoundCone
from synthesis.avatar.skinning import (
    linear_blend_skinning,
    skin_transforms,
    skin_weights,
)
from synthesis.rigs.hand import HandModel
from synthesis.skeleton.kinematics import Pose


def _finger():
    bones = (
        RoundCone("a", (0, 0, 0), (0, 0.05, 0), 0.01, 0.01),
        RoundCone("b", (0, 0.05, 0), (0, 0.09, 0), 0.01, 0.009),
    )
    rng = np.random.default_rng(0)
    vertices = rng.uniform((-0.01, -0.01, -0.01), (0.01, 0.1, 0.01), (500, 3))
    return bones, vertices


def test_weights_sum_to_one_with_at_most_four_bones():
    model = HandModel()
    rng = np.random.default_rng(3)
    vertices = rng.uniform(-0.05, 0.4, (300, 3))
    from synthesis.avatar.hand_mesh import bind_dofs, hand_primitives

    primitives = hand_primitives(model, bind_dofs(model), "right")
    index = {name: i for i, name in enumerate(model.skeleton.names)}
    weights = skin_weights(vertices, primitives, index)
    assert weights.joints.shape == (300, 4) and weights.weights.shape == (300, 4)
    assert np.allclose(weights.weights.sum(axis=1), 1.0)
    assert np.all(weights.weights >= 0)


def test_weights_cross_over_at_the_joint():
    bones, _ = _finger()
    points = np.array([[0.01, 0.02, 0], [0.01, 0.05, 0], [0.01, 0.08, 0]])
    weights = skin_weights(points, bones, {"a": 0, "b": 1})
    on_b = np.where(weights.joints == 1, weights.weights, 0).sum(axis=1)
    assert on_b[0] < 0.05 and abs(on_b[1] - 0.5) < 0.1 and on_b[2] > 0.95


def _pose(rotations: Rotation, positions: np.ndarray) -> Pose:
    return Pose(quaternions=rotations.as_quat()[None], positions_m=positions[None])


def test_bind_pose_leaves_the_mesh_unchanged_and_rigid_motion_moves_it_rigidly():
    bones, vertices = _finger()
    weights = skin_weights(vertices, bones, {"a": 0, "b": 1}).matrix(2)
    normals = np.tile([0.0, 0.0, 1.0], (len(vertices), 1))
    bind = _pose(Rotation.from_rotvec([[0, 0, 0], [0, 0, 0]]), np.array([[0, 0, 0], [0, 0.05, 0]]))
    same, _ = linear_blend_skinning(vertices, normals, weights, skin_transforms(bind, bind))
    assert np.allclose(same[0], vertices, atol=1e-15)
    turn = Rotation.from_rotvec([0.3, -0.2, 0.5])
    shift = np.array([0.1, -0.2, 0.3])
    moved_pose = _pose(Rotation.concatenate([turn, turn]), turn.apply(bind.positions_m[0]) + shift)
    moved, moved_normals = linear_blend_skinning(
        vertices, normals, weights, skin_transforms(moved_pose, bind)
    )
    assert np.allclose(moved[0], turn.apply(vertices) + shift, atol=1e-12)
    assert np.allclose(moved_normals[0], turn.apply(normals), atol=1e-12)


def test_matches_the_formula_vertex_by_vertex():
    """v' = Σ_j w_ij · G_j · B_j⁻¹ · v (seed 004 §4.2.2), computed the slow way."""
    bones, vertices = _finger()
    weights = skin_weights(vertices, bones, {"a": 0, "b": 1})
    bind_r = Rotation.from_rotvec([[0, 0, 0], [0.1, 0, 0]])
    bind = _pose(bind_r, np.array([[0, 0, 0], [0, 0.05, 0]]))
    posed_r = Rotation.from_rotvec([[0, 0.2, 0], [1.2, 0.2, 0]])
    posed = _pose(posed_r, np.array([[0.01, 0, 0], [0.01, 0.05, 0.01]]))

    def matrix(rotation, position):
        m = np.eye(4)
        m[:3, :3], m[:3, 3] = rotation.as_matrix(), position
        return m

    skinned, _ = linear_blend_skinning(
        vertices, np.tile([0, 0, 1.0], (500, 1)), weights.matrix(2), skin_transforms(posed, bind)
    )
    for k in (0, 17, 250, 499):
        total = np.zeros(4)
        for joint, w in zip(weights.joints[k], weights.weights[k], strict=True):
            g = matrix(posed_r[joint], posed.positions_m[0, joint])
            b = matrix(bind_r[joint], bind.positions_m[0, joint])
            total += w * (g @ np.linalg.inv(b) @ np.append(vertices[k], 1.0))
        assert np.allclose(skinned[0, k], total[:3], atol=1e-12)


def test_posing_selected_vertices_gives_those_of_the_whole_mesh():
    from synthesis.avatar.hand_mesh import hand_avatar
    from synthesis.fingerspelling.alphabet import letter_pose

    avatar = hand_avatar("right")
    pose = avatar.rig.pose(np.stack([letter_pose("A"), letter_pose("Y")]))
    select = [np.arange(len(part.vertices_m)) % 7 == 0 for part in avatar.parts]
    for (whole, whole_normals), (chosen, chosen_normals), mask in zip(
        avatar.deform_pose(pose), avatar.deform_pose(pose, select), select, strict=True
    ):
        np.testing.assert_allclose(chosen, whole[:, mask], atol=1e-12)
        np.testing.assert_allclose(chosen_normals, whole_normals[:, mask], atol=1e-12)
