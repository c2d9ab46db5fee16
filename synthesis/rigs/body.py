"""The upper-body model for sentences: spine, neck, head, both arms and both hands.

Joints (seed 003 §3.2–3.3): hips (root), three spine joints (lower, middle, upper),
neck, head; per side a clavicle with two DOFs (raise, forward), shoulder (3), elbow
(flexion), forearm twist, wrist (2) and the full hand of :class:`~synthesis.rigs.hand.HandModel`;
under the head the face's bones (:mod:`synthesis.rigs.face`).
Seed 003's torso frame is x right, y forward, z up; the engine's world is x to the
viewer's right, y up, z toward the viewer, with the signer facing the viewer, so the
signer's right arm hangs at −x.

All DOFs at zero: upright, arms hanging at the sides, palms toward the thighs. Each arm
joint's local frame then matches the hand model's (y along the bone, z out of the palm,
x toward the thumb), so the hands attach unchanged. The left side is the mirror image.
Body DOF names are plain (``spine_lower_flexion``, ``right_shoulder_flexion``); hand DOFs
keep the hand model's names behind the side (``right_index_mcp_flexion``) and their
literature names (``riIndexMCPy``).
"""

from dataclasses import dataclass
from functools import cached_property

import numpy as np

from synthesis.rigs.face import face_dofs, face_joints
from synthesis.rigs.hand import HandModel
from synthesis.rigs.rig import MIRROR_X, Dof, JointSpec, Rig, mirror_dof

SIDES = ("right", "left")
HIPS_HEIGHT_M = 1.0
UPPER_ARM_LENGTH_M = 0.29
# Hanging arm, right side: local y down, z (palm) toward the thigh (+x), x forward (+z).
_ARM_REST = np.array([[0.0, 0.0, 1.0], [0.0, -1.0, 0.0], [1.0, 0.0, 0.0]])
# Hand DOFs that only place a free-floating forearm; the arm does that in the body.
_FOREARM_PLACEMENT = ("forearm_tilt_side", "forearm_tilt_forward")

_TRUNK = (
    JointSpec("hips", "", (0.0, HIPS_HEIGHT_M, 0.0)),
    JointSpec("spine_lower", "hips", (0.0, 0.10, 0.0)),
    JointSpec("spine_middle", "spine_lower", (0.0, 0.13, 0.0)),
    JointSpec("spine_upper", "spine_middle", (0.0, 0.13, 0.0)),
    JointSpec("neck", "spine_upper", (0.0, 0.17, -0.01)),
    JointSpec("head", "neck", (0.0, 0.09, 0.01)),
    JointSpec("head_top", "head", (0.0, 0.20, 0.0), is_end=True),
)


def _trunk_dofs() -> list[Dof]:
    dofs = []
    limits = {
        "spine_lower": (30, 15, 20),
        "spine_middle": (30, 15, 20),
        "spine_upper": (30, 15, 20),
        "neck": (50, 30, 60),
        "head": (30, 20, 30),
    }
    for joint, (flex, side, turn) in limits.items():
        dofs += [
            # Flexion bends forward (toward +z); side bend leans to the signer's left (+x);
            # rotation turns the front toward the signer's left.
            Dof(f"{joint}_flexion", joint, "x", 1, -flex / 2, flex, f"{joint}_flexion"),
            Dof(f"{joint}_side_bend", joint, "z", -1, -side, side, f"{joint}_side_bend"),
            Dof(f"{joint}_rotation", joint, "y", 1, -turn, turn, f"{joint}_rotation"),
        ]
    return dofs


def _arm(side: str) -> tuple[list[JointSpec], list[Dof]]:
    """Return one arm's joints and DOFs (clavicle to fingertips), mirrored for the left."""
    p = side + "_"
    hand = HandModel(side)
    mirror = MIRROR_X if side == "left" else np.eye(3)
    joints = [
        JointSpec(p + "clavicle", "spine_upper", tuple(mirror @ (-0.02, 0.12, 0.02))),
        JointSpec(
            p + "shoulder",
            p + "clavicle",
            tuple(mirror @ (-0.155, 0.015, -0.03)),
            mirror @ _ARM_REST @ mirror,
        ),
        JointSpec(p + "elbow", p + "shoulder", (0.0, UPPER_ARM_LENGTH_M, 0.0)),
        JointSpec(p + "forearm", p + "elbow", (0.0, 0.0, 0.0)),
    ]
    for spec in hand.joint_specs[1:]:
        joints.append(
            JointSpec(
                p + spec.name, p + spec.parent, spec.offset_m, spec.rest_rotation, spec.is_end
            )
        )
    # Right-side DOFs in the arm's local frame (x forward, y down the arm, z medial).
    right = [
        Dof(p + "clavicle_raise", p + "clavicle", "z", -1, -10, 30, p + "clavicle_raise"),
        Dof(p + "clavicle_forward", p + "clavicle", "y", 1, -15, 25, p + "clavicle_forward"),
        Dof(p + "shoulder_flexion", p + "shoulder", "z", -1, -50, 180, p + "shoulder_flexion"),
        Dof(p + "shoulder_abduction", p + "shoulder", "x", -1, -30, 180, p + "shoulder_abduction"),
        Dof(p + "shoulder_rotation", p + "shoulder", "y", -1, -70, 90, p + "shoulder_rotation"),
        Dof(p + "elbow_flexion", p + "elbow", "z", -1, 0, 150, p + "elbow_flexion"),
    ]
    dofs = [mirror_dof(d) for d in right] if side == "left" else right
    for dof in hand.dofs:
        if dof.name in _FOREARM_PLACEMENT:
            continue
        dofs.append(
            Dof(
                p + dof.name,
                p + dof.joint,
                dof.axis,
                dof.sign,
                dof.min_deg,
                dof.max_deg,
                dof.literature,
            )
        )
    return joints, dofs


@dataclass(frozen=True)
class BodyModel(Rig):
    """The signer's upper body with both hands; *dominant* names the signing hand.

    *eye_centre_m* places the eyes' centres on the head (see :func:`face_joints`);
    nothing else, DOFs included, depends on it, so a motion of one body model plays on
    another.
    """

    dominant: str = "right"
    eye_centre_m: tuple[float, float, float] | None = None
    kind = "body"

    def __post_init__(self) -> None:
        if self.dominant not in SIDES:
            raise ValueError(f"dominant must be 'right' or 'left', not {self.dominant!r}.")

    @cached_property
    def _parts(self) -> tuple[tuple[JointSpec, ...], tuple[Dof, ...]]:
        # The face's joints follow the head's (a depth-first order, as BVH writes it);
        # its DOFs, the face channels, come last.
        joints, dofs = [*_TRUNK, *face_joints(self.eye_centre_m)], _trunk_dofs()
        for side in SIDES:
            arm_joints, arm_dofs = _arm(side)
            joints += arm_joints
            dofs += arm_dofs
        return tuple(joints), (*dofs, *face_dofs())

    @property
    def joint_specs(self) -> tuple[JointSpec, ...]:
        return self._parts[0]

    @property
    def dofs(self) -> tuple[Dof, ...]:
        return self._parts[1]

    def hand_dofs(self, side: str) -> np.ndarray:
        """Return, for one side, the body DOF index of each hand-model DOF (−1 if none).

        Lets a hand pose (a letter of the alphabet) be placed into a body pose.
        """
        index = {name: i for i, name in enumerate(self.dof_names)}
        return np.array(
            [index.get(f"{side}_{name}", -1) for name in HandModel(side).dof_names], dtype=np.intp
        )

    def with_hand(
        self, dofs_rad: np.ndarray, side: str, hand_dofs_rad: np.ndarray, digits_only: bool = False
    ) -> np.ndarray:
        """Return body DOF vectors with one hand set from hand-model DOF vectors.

        With *digits_only* the forearm twist and the wrist keep their values (an arm
        solved by IK has turned the hand already; a handshape only curls the digits).
        """
        dofs = np.array(dofs_rad, dtype=np.float64, copy=True)
        hand = np.asarray(hand_dofs_rad, dtype=np.float64)
        where = self.hand_dofs(side)
        kept = where >= 0
        if digits_only:
            names = HandModel(side).dof_names
            kept &= np.array([not name.startswith(("forearm_", "wrist_")) for name in names])
        dofs[..., where[kept]] = hand[..., kept]
        return dofs

    def mirror_pose(self, dofs_rad: np.ndarray) -> np.ndarray:
        """Return the mirror image (x ↦ −x) of body DOF vectors (..., n_dofs).

        The left side's DOFs are the right's mirrored, so sides swap values; the trunk's
        side bends and rotations (about z and y) change sign.
        """
        dofs = np.asarray(dofs_rad, dtype=np.float64)
        index = {name: i for i, name in enumerate(self.dof_names)}
        order = np.arange(len(self.dofs))
        sign = np.ones(len(self.dofs))
        for i, dof in enumerate(self.dofs):
            for a, b in (("right_", "left_"), ("left_", "right_")):
                if dof.name.startswith(a):
                    order[i] = index[b + dof.name.removeprefix(a)]
            if not dof.name.startswith(("right_", "left_")) and dof.axis in ("y", "z"):
                sign[i] = -1.0
        return dofs[..., order] * sign
