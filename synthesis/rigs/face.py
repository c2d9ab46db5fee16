"""The face's bones: eyes that turn for gaze, eyelids, brows, jaw, lips, cheeks, tongue.

Face bones are joints under the head, turned by DOFs like every other joint, so a face
is part of a body pose (its DOFs are the *face channels*), written to BVH and
interpolated, staggered and mirrored with the rest. Most face bones only need to slide
skin or a feature a few millimetres: such a bone's pivot sits far from what it moves, so
its rotation moves it almost in a straight line (a brow's pivot is 10 cm behind the
brow, so its raise slides the brow up the forehead). The eyes and eyelids turn about
the eyeball's centre.

Offsets are in the head's frame (x to the viewer's right = the signer's left, y up, z
forward), metres, written for the signer's right side (x < 0); the left side is its
mirror image. Each DOF's sign is chosen so that a positive value does what its name
says: ``right_brow_raise`` > 0 raises the brow, ``jaw_open`` > 0 opens the mouth.
:data:`EXPRESSIONS` names the face's poses (brow raise, blink, CHA, …) in degrees.
"""

from types import MappingProxyType

import numpy as np

from synthesis.rigs.rig import MIRROR_X, Dof, JointSpec, mirror_dof

# Where features sit on the head (its frame, metres; right side).
EYE_CENTRE_M = (-0.032, 0.108, 0.071)
EYE_RADIUS_M = 0.0115
MOUTH_HEIGHT_M = 0.038
MOUTH_HALF_WIDTH_M = 0.021

_SIDED_JOINTS = (
    # name, parent, offset (m, in the parent's frame)
    ("eye", "head", EYE_CENTRE_M),
    ("upper_lid", "head", EYE_CENTRE_M),
    ("lower_lid", "head", EYE_CENTRE_M),
    # Behind the brow and a little below, so that it slides along the sloping forehead
    # (with the skin under it: synthesis.avatar.face_mesh).
    ("brow", "head", (-0.030, 0.108, -0.020)),
    ("mouth_corner", "head", (-MOUTH_HALF_WIDTH_M, MOUTH_HEIGHT_M, -0.100)),
    ("cheek", "head", (-0.090, 0.050, -0.150)),  # outside the cheek: it puffs out and forward
)
_JAW_M = (0.0, 0.035, -0.050)
_MIDLINE_JOINTS = (
    ("jaw", "head", _JAW_M),
    # Children of the jaw: the lower lip and the tongue go down with it.
    ("lower_lip", "jaw", tuple(np.subtract((0.0, -0.030, 0.070), _JAW_M))),
    ("tongue", "jaw", tuple(np.subtract((0.0, -0.120, 0.050), _JAW_M))),
    ("upper_lip", "head", (0.0, 0.100, 0.070)),
)

# name, joint, axis, sign, min°, max°: right side (x < 0).
_SIDED_DOFS = (
    # Positive turns an eye toward the nose (the left eye's DOF is the right's mirror),
    # so a gaze to one side sets the two apart in sign (see gaze_degrees).
    ("eye_turn", "eye", "y", 1, -35, 35),
    ("eye_pitch", "eye", "x", 1, -25, 30),  # positive looks down
    ("upper_lid_close", "upper_lid", "x", 1, -20, 48),  # 48: shut; −20: wide open
    ("lower_lid_raise", "lower_lid", "x", -1, -10, 30),
    ("brow_raise", "brow", "x", -1, -5, 7),  # 1° ≈ 1.8 mm at the brow
    ("brow_squeeze", "brow", "y", 1, -2, 5),  # toward the midline
    ("mouth_corner_out", "mouth_corner", "y", -1, -4, 4),  # 1° ≈ 3.2 mm
    ("mouth_corner_up", "mouth_corner", "x", -1, -3, 4),
    ("cheek_puff", "cheek", "y", -1, 0, 4),  # 1° ≈ 3.5 mm outward
)
_MIDLINE_DOFS = (
    ("jaw_open", "jaw", "x", 1, -1, 12),  # 1° ≈ 2.3 mm at the lower lip
    ("lower_lip_forward", "lower_lip", "x", 1, -4, 8),
    ("upper_lip_forward", "upper_lip", "x", -1, -4, 8),
    ("tongue_out", "tongue", "x", 1, 0, 12),
)

SIDES = ("right", "left")


def face_joints(eye_centre_m=None) -> tuple[JointSpec, ...]:
    """Return the face's joints, in an order where each follows its parent.

    *eye_centre_m* puts the right eye's centre (and its lids' pivot) elsewhere on the
    head (its frame, m), for a face modelled apart from the rig (the human avatar's);
    the left eye mirrors it.
    """
    eye = EYE_CENTRE_M if eye_centre_m is None else tuple(eye_centre_m)
    joints = []
    for side in SIDES:
        mirror = MIRROR_X if side == "left" else np.eye(3)
        for name, parent, offset in _SIDED_JOINTS:
            offset = eye if offset == EYE_CENTRE_M else offset
            joints.append(JointSpec(f"{side}_{name}", parent, tuple(mirror @ offset)))
    joints += [JointSpec(name, parent, offset) for name, parent, offset in _MIDLINE_JOINTS]
    return tuple(joints)


def face_dofs() -> tuple[Dof, ...]:
    """Return the face channels: both sides' DOFs, then the midline's."""
    dofs = []
    for side in SIDES:
        for name, joint, axis, sign, low, high in _SIDED_DOFS:
            dof = Dof(f"{side}_{name}", f"{side}_{joint}", axis, sign, low, high, f"{side}_{name}")
            dofs.append(mirror_dof(dof) if side == "left" else dof)
    dofs += [
        Dof(name, joint, axis, sign, low, high, name)
        for name, joint, axis, sign, low, high in _MIDLINE_DOFS
    ]
    return tuple(dofs)


FACE_JOINT_NAMES = frozenset(joint.name for joint in face_joints())
FACE_DOF_NAMES = frozenset(dof.name for dof in face_dofs())
EYE_DOF_NAMES = frozenset(f"{side}_{name}" for side in SIDES for name in ("eye_turn", "eye_pitch"))


def is_face_dof(name: str) -> bool:
    """Return whether a body DOF is a face channel."""
    return name in FACE_DOF_NAMES


def gaze_degrees(turn_deg: float, pitch_deg: float = 0.0) -> dict[str, float]:
    """Return both eyes' DOFs (degrees) for a gaze *turn_deg* toward the signer's left
    (negative: right) and *pitch_deg* down (negative: up)."""
    return {
        "right_eye_turn": turn_deg,
        "left_eye_turn": -turn_deg,
        "right_eye_pitch": pitch_deg,
        "left_eye_pitch": pitch_deg,
    }


def both(**degrees: float) -> dict[str, float]:
    """Return sided face DOFs (degrees) set alike on both sides: ``both(brow_raise=6)``."""
    return {f"{side}_{name}": value for name, value in degrees.items() for side in SIDES}


# The face's poses, in degrees of its DOFs (an absent DOF is 0). Mouth shapes after the
# ASL mouth morphemes they show (Baker-Shenk & Cokely 1980): MM lips pressed together
# and pushed out, CHA the jaw dropped wide, OO rounded lips, TH the tongue between the
# lips, puffed cheeks; brows up for yes/no questions and topics, drawn down and together
# for wh-questions (seed 003 §4).
EXPRESSIONS = MappingProxyType(
    {
        "neutral": {},
        "brow raise": both(brow_raise=6.5, upper_lid_close=-8),
        "brow furrow": both(brow_raise=-4.5, brow_squeeze=4.5, upper_lid_close=6),
        "blink": both(upper_lid_close=48, lower_lid_raise=4),
        "squint": both(upper_lid_close=21, lower_lid_raise=22, cheek_puff=0.6),
        "wide eyes": both(upper_lid_close=-20, brow_raise=3),
        "gaze left": gaze_degrees(28),
        "gaze right": gaze_degrees(-28),
        "gaze up": {**gaze_degrees(0, -20), **both(upper_lid_close=-10)},
        "gaze down": {**gaze_degrees(0, 22), **both(upper_lid_close=22)},
        "mouth open": {"jaw_open": 9.0},
        "spread lips": both(mouth_corner_out=3.5, mouth_corner_up=1.5),
        # Corners up and the cheeks lifting the lower lids, the jaw just open (issue 52:
        # HAPPY as spread lips and a squint barely moved the human's face).
        "smile": {
            **both(mouth_corner_up=4.0, mouth_corner_out=1.5, lower_lid_raise=12),
            "jaw_open": 2.0,
        },
        "rounded lips (OO)": {
            **both(mouth_corner_out=-2.2),
            "jaw_open": 3.0,
            "upper_lip_forward": 6.0,
            "lower_lip_forward": 6.0,
        },
        "pursed lips (MM)": {
            **both(mouth_corner_out=-1.5),
            "upper_lip_forward": 3.0,
            "lower_lip_forward": 3.0,
            "jaw_open": -1.0,
        },
        "CHA": {"jaw_open": 12.0, **both(mouth_corner_out=1.5, brow_raise=2)},
        "TH": {"jaw_open": 2.5, "tongue_out": 4.5, "lower_lip_forward": 1.0},
        "puffed cheeks": {
            **both(cheek_puff=4.0, mouth_corner_out=-1.0),
            "upper_lip_forward": 2.0,
            "lower_lip_forward": 2.0,
        },
    }
)
