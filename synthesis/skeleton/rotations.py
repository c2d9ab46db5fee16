"""Vectorised rotation arithmetic on plain arrays, for the engine's hot paths.

Quaternions are scalar-last ``(x, y, z, w)`` like scipy's ``Rotation``; angles in
radians. scipy's ``Rotation`` remains the reference (and is used where speed does not
matter); these functions avoid its per-call overhead on (frames × joints) batches and
are tested against it.
"""

import warnings

import numpy as np
from scipy.spatial.transform import Rotation

_AXES = {"X": 0, "Y": 1, "Z": 2}


def quat_from_euler(angles_rad: np.ndarray, order: str) -> np.ndarray:
    """Return quaternions (..., 4) for intrinsic Euler angles (..., len(order)).

    Intrinsic order "ZXY" means ``R = Rz(a0) · Rx(a1) · Ry(a2)``, as in BVH channels
    and ``Rotation.from_euler("ZXY", …)``.
    """
    angles = np.asarray(angles_rad, dtype=np.float64)
    if len(order) != angles.shape[-1] or any(axis not in _AXES for axis in order):
        raise ValueError(f"Euler order {order!r} does not fit angles of shape {angles.shape}.")
    shape = angles.shape[:-1]
    # Axis-major half angles: one contiguous sin and cos call for everything, and
    # separate x, y, z, w arrays so that the products below are elementwise.
    half = 0.5 * np.moveaxis(angles, -1, 0)
    sines, cosines = np.sin(half), np.cos(half)
    parts = [np.zeros(shape), np.zeros(shape), np.zeros(shape), np.ones(shape)]
    for k, name in enumerate(order):
        sin, cos = sines[k], cosines[k]
        if k == 0:
            parts[_AXES[name]], parts[3] = sin, cos
            continue
        # q ⊗ (sin·e_axis, cos), written out for a single-axis rotation.
        axis = _AXES[name]
        after, second = (axis + 1) % 3, (axis + 2) % 3
        x = parts
        parts = list(x)  # each of its four is replaced below
        parts[axis] = x[axis] * cos + x[3] * sin
        parts[after] = x[after] * cos + x[second] * sin
        parts[second] = x[second] * cos - x[after] * sin
        parts[3] = x[3] * cos - x[axis] * sin
    return np.stack(parts, axis=-1)


def quat_conjugate(q: np.ndarray) -> np.ndarray:
    """Return the conjugate (the inverse, for unit quaternions) of quaternions (..., 4)."""
    return np.asarray(q) * np.array([-1.0, -1.0, -1.0, 1.0])


def quat_multiply(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Return the Hamilton product a ⊗ b (the rotation b, then a), shapes broadcast."""
    ax, ay, az, aw = np.moveaxis(np.asarray(a), -1, 0)
    bx, by, bz, bw = np.moveaxis(np.asarray(b), -1, 0)
    return np.stack(
        (
            aw * bx + ax * bw + ay * bz - az * by,
            aw * by - ax * bz + ay * bw + az * bx,
            aw * bz + ax * by - ay * bx + az * bw,
            aw * bw - ax * bx - ay * by - az * bz,
        ),
        axis=-1,
    )


def _cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    # np.cross is general (and slow) for small last axes; this is the plain formula.
    ax, ay, az = a[..., 0], a[..., 1], a[..., 2]
    bx, by, bz = b[..., 0], b[..., 1], b[..., 2]
    return np.stack((ay * bz - az * by, az * bx - ax * bz, ax * by - ay * bx), axis=-1)


def quat_rotate(q: np.ndarray, v: np.ndarray) -> np.ndarray:
    """Rotate vectors v (..., 3) by unit quaternions q (..., 4)."""
    q = np.asarray(q)
    vector, scalar = q[..., :3], q[..., 3:4]
    twice_cross = 2.0 * _cross(vector, v)
    return v + scalar * twice_cross + _cross(vector, twice_cross)


def quat_to_matrix(q: np.ndarray) -> np.ndarray:
    """Return rotation matrices (..., 3, 3) of unit quaternions (..., 4)."""
    x, y, z, w = np.moveaxis(np.asarray(q), -1, 0)
    xx, yy, zz = x * x, y * y, z * z
    xy, xz, yz = x * y, x * z, y * z
    wx, wy, wz = w * x, w * y, w * z
    matrix = np.stack(
        (
            1 - 2 * (yy + zz),
            2 * (xy - wz),
            2 * (xz + wy),
            2 * (xy + wz),
            1 - 2 * (xx + zz),
            2 * (yz - wx),
            2 * (xz - wy),
            2 * (yz + wx),
            1 - 2 * (xx + yy),
        ),
        axis=-1,
    )
    return matrix.reshape((*matrix.shape[:-1], 3, 3))


def euler_angles(rotation: Rotation, order: str, degrees: bool = False) -> np.ndarray:
    """Return *rotation*'s intrinsic Euler angles in *order*, without gimbal-lock warnings.

    At ±90° the angles are not unique; scipy picks one set (third angle zero) that gives
    the same rotation exactly, so the warning says nothing a caller must act on.
    """
    with warnings.catch_warnings():
        warnings.filterwarnings("ignore", "Gimbal lock detected", UserWarning)
        return rotation.as_euler(order, degrees=degrees)
