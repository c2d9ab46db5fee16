"""Body postures that carry a hand motion: the fingerspelling position.

Fingerspelling is signed with the dominant hand held up beside the chin, the elbow low,
palm toward the viewer. The hand model's motion says how the hand is turned and how the
forearm leans (its placement DOFs tilt a free forearm about the elbow for G, H, P, Q, J,
Z and double letters): the arm is solved by IK (:func:`synthesis.rigs.ik.solve_arm`)
for every frame so that the hand is turned as the hand model turns it, faced a little
toward the body's midline (and so toward a camera in front of the signer), and the
forearm leans from its spelling posture about the elbow as the hand model's forearm
leans from upright (the elbow stays put).
"""

import numpy as np
from scipy.spatial.transform import Rotation

from synthesis.rigs.body import BodyModel
from synthesis.rigs.hand import HandModel
from synthesis.rigs.ik import solve_arm
from synthesis.skeleton.rotations import quat_to_matrix

# The wrist's spelling position from the shoulder joint (m): toward the midline, below
# the shoulder and in front of it (right hand; the left mirrors x).
SPELLING_WRIST_FROM_SHOULDER_M = (0.022, -0.075, 0.286)
# The palm turns this far toward the body's midline (a signer faces the palm slightly in).
FACING_IN_DEG = 8.0
# The elbow hangs low, away from the body: at 20° G and H, held up in the fingerspelling
# space, could turn the index only to 22° from where the hand model points it (40°: 3°).
ELBOW_SWIVEL_DEG = 40.0
# How far below its spelling height a leaning forearm may carry the wrist (m).
MAX_WRIST_DROP_M = 0.04


def fingerspelling_posture(body: BodyModel, side: str, hand_dofs_rad: np.ndarray) -> np.ndarray:
    """Return body DOF vectors (n_frames, n_dofs) holding the hand up for hand-model DOFs."""
    hand = HandModel(side)
    hand_dofs = np.atleast_2d(hand_dofs_rad)
    wrist, forearm = hand.skeleton.index("wrist"), hand.skeleton.index("forearm")
    moved = hand.pose(hand_dofs)
    inward = 1.0 if side == "right" else -1.0
    facing = Rotation.from_euler("y", inward * FACING_IN_DEG, degrees=True).as_matrix()
    index = body.skeleton.index
    shoulder = body.pose(body.neutral()).positions_m[0, index(f"{side}_shoulder")]
    spelling = shoulder + hand.mirror @ np.asarray(SPELLING_WRIST_FROM_SHOULDER_M) * [-1, 1, 1]
    # The spelling posture itself: the forearm upright in the hand model.
    rest = solve_arm(body, body.neutral(), side, spelling, facing, np.radians(ELBOW_SWIVEL_DEG))
    at_rest = body.pose(rest).positions_m[0]
    elbow = at_rest[index(f"{side}_elbow")]
    forearm_m = at_rest[index(f"{side}_wrist")] - elbow
    leaning = moved.positions_m[:, wrist] - moved.positions_m[:, forearm]
    lean = _least_turns(np.array([0.0, 1.0, 0.0]), leaning)
    # The wrist goes where the leaning forearm takes it, forward and across, but stays
    # up in the fingerspelling space (issue 52: leaning about a low elbow dropped P and
    # Q's hands to the hip, G and H's to the breastbone): the arm lifts instead.
    moved_by = np.einsum("fij,j->fi", lean, forearm_m) - forearm_m
    moved_by[:, 1] = np.maximum(moved_by[:, 1], -MAX_WRIST_DROP_M)
    targets = elbow + forearm_m + moved_by
    rotations = facing @ quat_to_matrix(moved.quaternions[:, wrist])
    dofs = body.with_hand(np.repeat(body.neutral()[None], len(hand_dofs), axis=0), side, hand_dofs)
    return solve_arm(body, dofs, side, targets, rotations, np.radians(ELBOW_SWIVEL_DEG))


def _least_turns(start: np.ndarray, ends: np.ndarray) -> np.ndarray:
    """Return the least rotations (n, 3, 3) taking the unit direction *start* to *ends*."""
    ends = ends / np.linalg.norm(ends, axis=1, keepdims=True)
    axes = np.cross(start, ends)
    sines = np.linalg.norm(axes, axis=1)
    angles = np.arctan2(sines, ends @ start)
    vectors = np.where(sines[:, None] > 1e-12, axes / np.maximum(sines, 1e-12)[:, None], 0.0)
    return Rotation.from_rotvec(vectors * angles[:, None]).as_matrix()


def hand_motion_on(rig, side: str, hand_dofs_rad: np.ndarray) -> np.ndarray:
    """Return *rig*'s DOFs for hand-model DOFs: the hand itself, or a body holding it up."""
    if isinstance(rig, HandModel):
        return hand_dofs_rad
    return fingerspelling_posture(rig, side, hand_dofs_rad)
