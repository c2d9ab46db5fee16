"""Test the vectorised rotation helpers against scipy.spatial.transform.Rotation."""

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from synthesis.skeleton.rotations import quat_from_euler, quat_multiply, quat_rotate, quat_to_matrix

ORDERS = ["XYZ", "XZY", "YXZ", "YZX", "ZXY", "ZYX", "ZXZ", "XYX", "Z", "XY"]


def _same_rotation(q: np.ndarray, r: Rotation) -> bool:
    # q and −q are the same rotation; compare as matrices.
    return np.allclose(quat_to_matrix(q), r.as_matrix(), atol=1e-12)


@pytest.mark.parametrize("order", ORDERS)
def test_from_euler_matches_scipy_intrinsic(order):
    angles = np.random.default_rng(len(order)).uniform(-np.pi, np.pi, (5, 7, len(order)))
    q = quat_from_euler(angles, order)
    assert q.shape == (5, 7, 4)
    reference = Rotation.from_euler(order, angles.reshape(-1, len(order)))
    assert _same_rotation(q.reshape(-1, 4), reference)
    assert np.allclose(np.linalg.norm(q, axis=-1), 1.0)


def test_round_trip_through_scipy_euler():
    angles = np.random.default_rng(2).uniform(-1.5, 1.5, (100, 3))
    q = quat_from_euler(angles, "ZXY")
    back = Rotation.from_quat(q).as_euler("ZXY")
    assert np.allclose(back, angles, atol=1e-12)


def test_multiply_rotate_and_matrix_match_scipy():
    rng = np.random.default_rng(9)
    a, b = Rotation.random(50, random_state=rng), Rotation.random(50, random_state=rng)
    vectors = rng.normal(size=(50, 3))
    product = quat_multiply(a.as_quat(), b.as_quat())
    assert _same_rotation(product, a * b)
    assert np.allclose(quat_rotate(a.as_quat(), vectors), a.apply(vectors), atol=1e-12)
    assert np.allclose(quat_to_matrix(a.as_quat()), a.as_matrix(), atol=1e-12)


def test_bad_order_is_rejected():
    with pytest.raises(ValueError, match="does not fit"):
        quat_from_euler(np.zeros((2, 3)), "ZX")
    with pytest.raises(ValueError, match="does not fit"):
        quat_from_euler(np.zeros((2, 3)), "ZXW")
