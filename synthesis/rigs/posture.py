"""Body postures that carry a hand motion: the fingerspelling position.

Fingerspelling is signed with the dominant hand held up beside the chin, the elbow low
and bent, palm toward the viewer. The hand model's forearm placement DOFs (its own
"tilt" of a free forearm, used by G, H, P, Q, J, Z and double letters) become the arm's
motion: a sideways tilt turns the upper arm inward, a forward tilt opens the elbow.
"""

import numpy as np

from synthesis.rigs.body import BodyModel
from synthesis.rigs.hand import HandModel

FINGERSPELLING_DEGREES = {
    "shoulder_flexion": 25.0,
    "shoulder_abduction": 12.0,
    "shoulder_rotation": 15.0,
    "elbow_flexion": 115.0,
}
# Added to the hand's own forearm twist: the palm turns a little toward the viewer.
FOREARM_TWIST_DEG = 10.0


def fingerspelling_posture(body: BodyModel, side: str, hand_dofs_rad: np.ndarray) -> np.ndarray:
    """Return body DOF vectors (n_frames, n_dofs) holding the hand up for hand-model DOFs."""
    hand = HandModel(side)
    hand_dofs_rad = np.atleast_2d(hand_dofs_rad)
    base = body.from_degrees({f"{side}_{k}": v for k, v in FINGERSPELLING_DEGREES.items()})
    dofs = body.with_hand(np.repeat(base[None], len(hand_dofs_rad), axis=0), side, hand_dofs_rad)
    dofs[:, body.dof_names.index(f"{side}_forearm_twist")] += np.radians(FOREARM_TWIST_DEG)
    tilt_side = hand_dofs_rad[:, hand.dof_names.index("forearm_tilt_side")]
    tilt_forward = hand_dofs_rad[:, hand.dof_names.index("forearm_tilt_forward")]
    dofs[:, body.dof_names.index(f"{side}_shoulder_rotation")] -= tilt_side
    dofs[:, body.dof_names.index(f"{side}_elbow_flexion")] -= tilt_forward
    return body.clip(dofs)


def hand_motion_on(rig, side: str, hand_dofs_rad: np.ndarray) -> np.ndarray:
    """Return *rig*'s DOFs for hand-model DOFs: the hand itself, or a body holding it up."""
    if isinstance(rig, HandModel):
        return hand_dofs_rad
    return fingerspelling_posture(rig, side, hand_dofs_rad)
