"""Analytic two-bone arm IK for the body model, with elbow swivel and hand orientation.

Given where the wrist should be and which way the palm and fingers should face, solve
the shoulder (3 DOFs), elbow, forearm twist and wrist (2 DOFs) of one arm, the trunk and
clavicle staying as they are (the spine extension runs first, seed 003 §3). The elbow
lies on the circle of positions that keep both bones' lengths; *swivel* picks where:
0 hangs it as low as it goes, positive lifts it away from the body. Solving at sparse
key postures and easing the joint angles between them moves the hands in arcs, not
straight lines (seed 003 §2.1.4).

Positions are the engine's world (metres; x to the viewer's right, y up, z toward the
viewer); a hand orientation is the wrist joint's world frame, built from palm and finger
directions by :func:`hand_frame`.
"""

from functools import cache

import numpy as np
from scipy.spatial.transform import Rotation

from synthesis.rigs.body import BodyModel
from synthesis.skeleton.rotations import euler_angles, quat_to_matrix


def _unit(v: np.ndarray) -> np.ndarray:
    return v / np.linalg.norm(v, axis=-1, keepdims=True).clip(1e-12)


def hand_frame(palm: np.ndarray, fingers: np.ndarray) -> np.ndarray:
    """Return the wrist's world rotation (3, 3): local z along *palm* (out of the palm),
    local y along *fingers* (made orthogonal to the palm), x = y × z."""
    z = _unit(np.asarray(palm, dtype=float))
    y = np.asarray(fingers, dtype=float)
    y = _unit(y - np.dot(y, z) * z)
    return np.column_stack([np.cross(y, z), y, z])


@cache
def _bend_sign(side: str) -> float:
    """Return +1 if the shoulder's local z is along upper-arm × forearm for a bent elbow."""
    body = BodyModel()
    dofs = body.from_degrees({f"{side}_elbow_flexion": 90.0})
    pose = body.pose(dofs)
    index = body.skeleton.index
    p = pose.positions_m[0]
    upper = p[index(f"{side}_elbow")] - p[index(f"{side}_shoulder")]
    fore = p[index(f"{side}_wrist")] - p[index(f"{side}_elbow")]
    z = quat_to_matrix(pose.quaternions[0, index(f"{side}_shoulder")])[:, 2]
    return float(np.sign(np.dot(np.cross(upper, fore), z)))


def _joint_dofs(body: BodyModel, joint: str) -> tuple[np.ndarray, list[tuple[int, int, float]]]:
    """Return a joint's rest rotation and its DOFs as (dof index, ZXY column, sign)."""
    spec = next(s for s in body.joint_specs if s.name == joint)
    rest = np.eye(3) if spec.rest_rotation is None else spec.rest_rotation
    column = {"z": 0, "x": 1, "y": 2}
    dofs = [(i, column[d.axis], d.sign) for i, d in enumerate(body.dofs) if d.joint == joint]
    return rest, dofs


def _set_joint(body: BodyModel, dofs: np.ndarray, joint: str, local: np.ndarray) -> None:
    """Write the DOFs of *joint* that make its local rotations *local* (n, 3, 3), in place.

    The rig's local rotation is the rest rotation then ZXY Euler angles; angles about
    axes the joint has no DOF for are dropped.
    """
    rest, joint_dofs = _joint_dofs(body, joint)
    angles = euler_angles(Rotation.from_matrix(rest.T @ local), "ZXY")
    for index, column, sign in joint_dofs:
        dofs[:, index] = angles[:, column] / sign


def _swing(n: np.ndarray, swivel: np.ndarray, side: str) -> np.ndarray:
    """Return the unit directions (n, 3), normal to the reach *n*, the elbow swings to:
    *swivel* from straight down, outward (away from the body) for positive angles."""
    down = np.array([0.0, -1.0, 0.0]) - n[:, 1:2] * -n
    vertical = np.linalg.norm(down, axis=1) < 1e-6
    if vertical.any():  # reaching straight up or down: swivel from forward
        down[vertical] = np.array([0.0, 0.0, 1.0]) - n[vertical, 2:3] * n[vertical]
    down = _unit(down)
    outward = -1.0 if side == "right" else 1.0
    return np.cos(swivel) * down + np.sin(swivel) * outward * np.cross(n, down)


def _turn_hand(body, dofs, p: str, upper_arm, elbow_index: int, target) -> None:
    """Set the forearm twist and wrist DOFs that turn the hand to *target* (n, 3, 3)."""
    # The forearm's frame before its twist: the shoulder's, turned by the elbow.
    elbow_dof = body.dofs[elbow_index]
    bend = Rotation.from_euler(elbow_dof.axis, dofs[:, elbow_index, None] * elbow_dof.sign)
    forearm = upper_arm @ bend.as_matrix()
    twist, deviation, flexion = euler_angles(
        Rotation.from_matrix(np.transpose(forearm, (0, 2, 1)) @ target), "YZX"
    ).T
    _set_joint(body, dofs, p + "forearm", Rotation.from_euler("Y", twist[:, None]).as_matrix())
    wrist_local = Rotation.from_euler("ZX", np.stack([deviation, flexion], axis=1))
    _set_joint(body, dofs, p + "wrist", wrist_local.as_matrix())


def solve_arm(
    body: BodyModel,
    dofs_rad: np.ndarray,
    side: str,
    wrist_m: np.ndarray,
    hand_rotation: np.ndarray | None = None,
    swivel_rad=0.3,
) -> np.ndarray:
    """Return body DOFs (n, n_dofs) with one arm reaching *wrist_m* (n, 3), world metres.

    Vectorised over postures; a single posture (n_dofs,) or target (3,) is shared by all,
    and both single give (n_dofs,).
    A target out of reach is approached along the line to it with the arm straight.
    *hand_rotation* (n, 3, 3), the wrist's world frame, sets forearm twist and wrist; the
    joint limits then clip what the wrist cannot reach. *swivel_rad* is one angle or
    one per posture.
    """
    single = np.ndim(dofs_rad) == 1 and np.ndim(wrist_m) == 1
    wrist = np.atleast_2d(np.asarray(wrist_m, dtype=float))
    n_keys = max(len(np.atleast_2d(dofs_rad)), len(wrist))
    dofs = np.array(np.broadcast_to(np.atleast_2d(dofs_rad), (n_keys, np.shape(dofs_rad)[-1])))
    wrist = np.broadcast_to(wrist, (n_keys, 3))
    p = side + "_"
    arm_joints = (p + "shoulder", p + "elbow", p + "forearm", p + "wrist")
    arm = [i for i, d in enumerate(body.dofs) if d.joint in arm_joints]
    dofs[:, arm] = 0.0
    index = body.skeleton.index
    offsets = body.skeleton.offsets
    upper = float(np.linalg.norm(offsets[index(p + "elbow")]))
    fore = float(np.linalg.norm(offsets[index(p + "wrist")]))
    pose = body.pose(dofs)
    shoulder = pose.positions_m[:, index(p + "shoulder")]
    clavicle = quat_to_matrix(pose.quaternions[:, index(p + "clavicle")])
    to_target = wrist - shoulder
    distance = np.clip(
        np.linalg.norm(to_target, axis=1), abs(upper - fore) + 1e-4, upper + fore - 1e-4
    )[:, None]
    n = _unit(to_target)
    swivel = np.broadcast_to(np.asarray(swivel_rad, dtype=float), (n_keys,))[:, None]
    swing = _swing(n, swivel, side)
    # The elbow's circle: angle at the shoulder by the law of cosines.
    cos_a = (upper**2 + distance**2 - fore**2) / (2 * upper * distance)
    elbow = shoulder + upper * (cos_a * n + np.sqrt(np.clip(1 - cos_a**2, 0.0, None)) * swing)
    y = _unit(elbow - shoulder)
    # upper × forearm is along swing × n for this elbow.
    z = -_bend_sign(side) * np.cross(n, swing)
    z = _unit(z - np.sum(z * y, axis=1, keepdims=True) * y)
    world = np.stack([np.cross(y, z), y, z], axis=2)
    _set_joint(body, dofs, p + "shoulder", np.transpose(clavicle, (0, 2, 1)) @ world)
    cos_b = (upper**2 + fore**2 - distance[:, 0] ** 2) / (2 * upper * fore)
    elbow_index = body.dof_names.index(p + "elbow_flexion")
    dofs[:, elbow_index] = np.pi - np.arccos(np.clip(cos_b, -1.0, 1.0))
    if hand_rotation is not None:
        target = np.broadcast_to(np.asarray(hand_rotation, dtype=float), (n_keys, 3, 3))
        _turn_hand(body, dofs, p, world, elbow_index, target)
    dofs = body.clip(dofs)
    return dofs[0] if single else dofs


# Elbow swivels tried when the key's own one cannot turn the hand as asked (rad).
SWIVEL_CANDIDATES_RAD = np.radians(np.arange(-60.0, 161.0, 20.0))
# A key keeps its own swivel unless another turns the hand this much closer (rad)...
_BETTER_RAD = np.radians(10.0)
# ...and its own misses by more than this.
_MISSED_RAD = np.radians(20.0)


def hand_turn_error(
    body: BodyModel, dofs_rad: np.ndarray, side: str, hand_rotation: np.ndarray
) -> np.ndarray:
    """Return the angle (rad, (n,)) between the wrists' world frames and *hand_rotation*."""
    pose = body.pose(np.atleast_2d(dofs_rad))
    found = quat_to_matrix(pose.quaternions[:, body.skeleton.index(f"{side}_wrist")])
    relative = np.transpose(found, (0, 2, 1)) @ np.asarray(hand_rotation)
    cosine = (np.trace(relative, axis1=-2, axis2=-1) - 1.0) / 2.0
    return np.arccos(np.clip(cosine, -1.0, 1.0))


def solve_arm_turning(
    body: BodyModel,
    dofs_rad: np.ndarray,
    side: str,
    wrist_m: np.ndarray,
    hand_rotation: np.ndarray,
    swivel_rad,
) -> np.ndarray:
    """Return :func:`solve_arm`'s DOFs (n, n_dofs), but where the joint limits keep a key's
    hand from turning as asked with its swivel, with the elbow where it turns closest.

    A palm asked to face the signer's midline with the fingers pointing back (the index
    of ME at the chest) needs the elbow out to the side: hung low, the wrist cannot bend
    that far. Each key keeps its own swivel unless it misses the hand's turn by more than
    20° and another of :data:`SWIVEL_CANDIDATES_RAD` comes 10° closer.
    """
    rotation = np.asarray(hand_rotation, dtype=float)
    own = solve_arm(body, dofs_rad, side, wrist_m, rotation, swivel_rad)
    n_keys = len(own)
    best, best_error = own, hand_turn_error(body, own, side, rotation)
    missed = best_error > _MISSED_RAD
    if not missed.any():
        return own
    for candidate in SWIVEL_CANDIDATES_RAD:
        trial = solve_arm(body, dofs_rad, side, wrist_m, rotation, np.full(n_keys, candidate))
        error = hand_turn_error(body, trial, side, rotation)
        better = missed & (error < best_error - _BETTER_RAD)
        best = np.where(better[:, None], trial, best)
        best_error = np.where(better, error, best_error)
    return best
