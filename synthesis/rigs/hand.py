"""The hand model: forearm, wrist and 15 finger joints, their DOFs, limits and names.

Hand frame (right hand; the left hand mirrors x): origin at the wrist joint, +y along
the middle metacarpal toward the fingers, +z out of the palm, +x toward the thumb.
With the forearm at rest the hand frame equals the engine's world frame (x to the
viewer's right, y up, z toward the viewer): a right hand held up, palm to the viewer.

Each digit's first joint has a fixed rest rotation (the fan of the fingers, the thumb's
angle to the palm); its DOFs rotate relative to it, so every bone lies along its joint's
local +y and flexes about local +x. Per hand there are 25 digit curves named as in seed
002 §3 (``riIndexMCPy``: side, digit, joint, axis; x = ab/adduction and y = flexion for
fingers, z = flexion for the thumb; finger MCPs also have a small axial z), plus wrist
flexion and deviation and the forearm's orientation and twist.

Segment lengths follow the proportions of Buchholz, Armstrong & Goldstein (1992,
"Anthropometric data for describing the kinematics of the human hand") for a 19 cm
hand.
"""

from dataclasses import dataclass
from functools import cached_property

import numpy as np
from scipy.spatial.transform import Rotation

from synthesis.rigs.rig import MIRROR_X, Dof, JointSpec, Rig, mirror_dof

FINGERS = ("index", "middle", "ring", "pinky")
DIGITS = ("thumb", *FINGERS)
_LITERATURE_DIGIT = {
    "thumb": "Thumb",
    "index": "Index",
    "middle": "Middle",
    "ring": "Ring",
    "pinky": "Pinky",
}

# Joint centres and segment lengths, metres, right hand frame.
FOREARM_LENGTH_M = 0.26
MCP_POSITIONS_M = {
    "index": (0.026, 0.088, 0.002),
    "middle": (0.007, 0.091, 0.0),
    "ring": (-0.011, 0.086, 0.003),
    "pinky": (-0.027, 0.077, 0.008),
}
# Proximal, middle, distal phalanx (DIP to fingertip) per finger.
PHALANX_LENGTHS_M = {
    "index": (0.046, 0.026, 0.022),
    "middle": (0.050, 0.030, 0.024),
    "ring": (0.047, 0.029, 0.023),
    "pinky": (0.037, 0.021, 0.020),
}
# Fan of the fingers at rest: angle toward the thumb side, degrees.
FINGER_FAN_DEG = {"index": 5.0, "middle": 0.0, "ring": -5.0, "pinky": -11.0}
THUMB_CMC_POSITION_M = (0.021, 0.022, 0.011)
# Metacarpal, proximal phalanx, distal phalanx (IP to tip).
THUMB_LENGTHS_M = (0.046, 0.034, 0.028)
# Thumb metacarpal direction at rest and the way its pad faces (hand frame).
THUMB_DIRECTION = (0.64, 0.75, 0.14)
THUMB_PAD_TOWARD = (-0.55, 0.1, 0.83)


def _dofs(side: str) -> tuple[Dof, ...]:
    prefix = "ri" if side == "right" else "le"
    table = [
        # Forearm orientation in the world: not anatomical angles, the arm's placement.
        Dof("forearm_tilt_side", "forearm", "z", 1, -100, 100, f"{prefix}ForearmZ"),
        Dof("forearm_tilt_forward", "forearm", "x", 1, -100, 100, f"{prefix}ForearmX"),
        # Positive twist turns the palm toward the signer's midline (pronation).
        Dof("forearm_twist", "forearm", "y", 1, -100, 100, f"{prefix}ForearmY"),
        Dof("wrist_deviation", "wrist", "z", -1, -30, 20, f"{prefix}Wristx"),
        Dof("wrist_flexion", "wrist", "x", 1, -70, 80, f"{prefix}Wristy"),
    ]
    # Thumb: CMC abduction (away from the palm), axial rotation (opposition), flexion.
    table += [
        Dof("thumb_cmc_abduction", "thumb_cmc", "z", -1, -30, 80, f"{prefix}ThumbCMCx"),
        Dof("thumb_cmc_rotation", "thumb_cmc", "y", 1, -30, 60, f"{prefix}ThumbCMCy"),
        Dof("thumb_cmc_flexion", "thumb_cmc", "x", 1, -45, 60, f"{prefix}ThumbCMCz"),
        Dof("thumb_mcp_flexion", "thumb_mcp", "x", 1, -20, 75, f"{prefix}ThumbMCPz"),
        Dof("thumb_ip_flexion", "thumb_ip", "x", 1, -25, 90, f"{prefix}ThumbIPz"),
    ]
    for finger in FINGERS:
        digit = _LITERATURE_DIGIT[finger]
        # Positive abduction moves the finger toward the thumb side (radially).
        table += [
            Dof(
                f"{finger}_mcp_abduction", f"{finger}_mcp", "z", -1, -25, 25, f"{prefix}{digit}MCPx"
            ),
            Dof(f"{finger}_mcp_flexion", f"{finger}_mcp", "x", 1, -30, 95, f"{prefix}{digit}MCPy"),
            Dof(f"{finger}_mcp_twist", f"{finger}_mcp", "y", 1, -15, 15, f"{prefix}{digit}MCPz"),
            Dof(f"{finger}_pip_flexion", f"{finger}_pip", "x", 1, -5, 110, f"{prefix}{digit}PIPy"),
            Dof(f"{finger}_dip_flexion", f"{finger}_dip", "x", 1, -10, 90, f"{prefix}{digit}DIPy"),
        ]
    return tuple(table)


def _unit(vector) -> np.ndarray:
    vector = np.asarray(vector, dtype=np.float64)
    return vector / np.linalg.norm(vector)


def _thumb_rest_rotation() -> np.ndarray:
    """Return the thumb CMC's rest rotation: local y along the thumb, local z to its pad."""
    y = _unit(THUMB_DIRECTION)
    z = _unit(np.asarray(THUMB_PAD_TOWARD) - np.dot(THUMB_PAD_TOWARD, y) * y)
    x = np.cross(y, z)
    return np.column_stack((x, y, z))


@dataclass(frozen=True)
class HandModel(Rig):
    """A right or left hand with its forearm: skeleton, DOFs and limits."""

    side: str = "right"
    kind = "hand"

    def __post_init__(self) -> None:
        if self.side not in ("right", "left"):
            raise ValueError(f"side must be 'right' or 'left', not {self.side!r}.")

    @cached_property
    def dofs(self) -> tuple[Dof, ...]:
        table = _dofs(self.side)
        return tuple(mirror_dof(d) for d in table) if self.side == "left" else table

    @cached_property
    def mirror(self) -> np.ndarray:
        """Return the reflection from right-hand to this hand's coordinates (identity or x ↦ −x)."""
        return MIRROR_X if self.side == "left" else np.eye(3)

    @cached_property
    def joint_specs(self) -> tuple[JointSpec, ...]:
        """Return the joints, parents first, offsets and rest rotations in this hand's frame."""
        rest = {"thumb_cmc": _thumb_rest_rotation()}
        joints = [
            JointSpec("forearm", "", (0.0, 0.0, 0.0)),
            JointSpec("wrist", "forearm", (0.0, FOREARM_LENGTH_M, 0.0)),
            JointSpec("thumb_cmc", "wrist", THUMB_CMC_POSITION_M),
        ]
        parent = "thumb_cmc"
        for name, length in zip(
            ("thumb_mcp", "thumb_ip", "thumb_tip"), THUMB_LENGTHS_M, strict=True
        ):
            joints.append(JointSpec(name, parent, (0.0, length, 0.0), is_end=name == "thumb_tip"))
            parent = name
        for finger in FINGERS:
            fan = np.radians(FINGER_FAN_DEG[finger])
            rest[f"{finger}_mcp"] = Rotation.from_euler("z", -fan).as_matrix()
            joints.append(JointSpec(f"{finger}_mcp", "wrist", MCP_POSITIONS_M[finger]))
            parent = f"{finger}_mcp"
            for name, length in zip(("pip", "dip", "tip"), PHALANX_LENGTHS_M[finger], strict=True):
                joints.append(
                    JointSpec(f"{finger}_{name}", parent, (0.0, length, 0.0), is_end=name == "tip")
                )
                parent = f"{finger}_{name}"
        return tuple(
            JointSpec(
                j.name,
                j.parent,
                tuple(float(v) for v in self.mirror @ np.asarray(j.offset_m)),
                None if j.name not in rest else self.mirror @ rest[j.name] @ self.mirror,
                j.is_end,
            )
            for j in joints
        )
