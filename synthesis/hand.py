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

from synthesis.kinematics import Pose, forward_kinematics_arrays
from synthesis.rotations import quat_from_euler, quat_multiply
from synthesis.skeleton import Joint, Skeleton

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


@dataclass(frozen=True)
class Dof:
    """One degree of freedom: which joint, which local axis, sign, limits (degrees)."""

    name: str
    joint: str
    axis: str
    sign: float
    min_deg: float
    max_deg: float
    literature: str


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
class HandModel:
    """A right or left hand with its forearm: skeleton, DOFs and limits."""

    side: str = "right"

    def __post_init__(self) -> None:
        if self.side not in ("right", "left"):
            raise ValueError(f"side must be 'right' or 'left', not {self.side!r}.")

    @cached_property
    def dofs(self) -> tuple[Dof, ...]:
        return _dofs(self.side)

    @cached_property
    def dof_names(self) -> list[str]:
        return [dof.name for dof in self.dofs]

    @cached_property
    def literature_names(self) -> list[str]:
        return [dof.literature for dof in self.dofs]

    @cached_property
    def limits_rad(self) -> tuple[np.ndarray, np.ndarray]:
        """Return the lower and upper limit of every DOF, radians."""
        return (
            np.radians([dof.min_deg for dof in self.dofs]),
            np.radians([dof.max_deg for dof in self.dofs]),
        )

    @cached_property
    def mirror(self) -> np.ndarray:
        """Return the reflection from right-hand to this hand's coordinates (identity or x ↦ −x)."""
        return np.diag([-1.0 if self.side == "left" else 1.0, 1.0, 1.0])

    @cached_property
    def _structure(self) -> tuple[list[tuple[str, str, np.ndarray]], dict[str, np.ndarray]]:
        """Return (joint, parent, offset) in the right-hand frame, and rest rotations."""
        joints: list[tuple[str, str, np.ndarray]] = [
            ("forearm", "", np.zeros(3)),
            ("wrist", "forearm", np.array([0.0, FOREARM_LENGTH_M, 0.0])),
        ]
        rest: dict[str, np.ndarray] = {}
        thumb_rest = _thumb_rest_rotation()
        rest["thumb_cmc"] = thumb_rest
        joints.append(("thumb_cmc", "wrist", np.array(THUMB_CMC_POSITION_M)))
        parent = "thumb_cmc"
        for name, length in zip(
            ("thumb_mcp", "thumb_ip", "thumb_tip"), THUMB_LENGTHS_M, strict=True
        ):
            joints.append((name, parent, np.array([0.0, length, 0.0])))
            parent = name
        for finger in FINGERS:
            fan = np.radians(FINGER_FAN_DEG[finger])
            rest[f"{finger}_mcp"] = Rotation.from_euler("z", -fan).as_matrix()
            joints.append((f"{finger}_mcp", "wrist", np.array(MCP_POSITIONS_M[finger])))
            parent = f"{finger}_mcp"
            for name, length in zip(("pip", "dip", "tip"), PHALANX_LENGTHS_M[finger], strict=True):
                joints.append((f"{finger}_{name}", parent, np.array([0.0, length, 0.0])))
                parent = f"{finger}_{name}"
        return joints, rest

    @cached_property
    def skeleton(self) -> Skeleton:
        """Return the hand as a BVH skeleton (metres; ZXY rotation channels)."""
        joints_spec, _ = self._structure
        names = [name for name, _, _ in joints_spec]
        joints = []
        for name, parent, offset in joints_spec:
            end = name.endswith("_tip")
            channels = () if end else ("Zrotation", "Xrotation", "Yrotation")
            mirrored = tuple(float(v) for v in self.mirror @ offset)
            joints.append(
                Joint(
                    name,
                    names.index(parent) if parent else -1,
                    mirrored,
                    channels,
                    is_end_site=end,
                )
            )
        return Skeleton(tuple(joints), length_unit="m")

    def clip(self, dofs_rad: np.ndarray) -> np.ndarray:
        """Return the DOF values clamped to the joint limits."""
        low, high = self.limits_rad
        return np.clip(dofs_rad, low, high)

    def neutral(self) -> np.ndarray:
        """Return the all-zero pose: fingers straight together, thumb at rest, palm forward."""
        return np.zeros(len(self.dofs))

    def from_degrees(self, angles_deg: dict[str, float]) -> np.ndarray:
        """Return a DOF vector (radians) from DOF names (or literature names) in degrees."""
        values = self.neutral()
        lookup = {dof.name: i for i, dof in enumerate(self.dofs)}
        lookup.update({dof.literature: i for i, dof in enumerate(self.dofs)})
        for name, angle in angles_deg.items():
            if name not in lookup:
                raise KeyError(f"Unknown hand DOF {name!r}.")
            values[lookup[name]] = np.radians(angle)
        return values

    @cached_property
    def _angle_map(self) -> tuple[np.ndarray, np.ndarray]:
        """Return (n_dofs, n_joints·3) DOF → ZXY-angle matrix and (n_joints, 4) rest quaternions."""
        joints_spec, rest = self._structure
        names = [name for name, _, _ in joints_spec]
        column = {"z": 0, "x": 1, "y": 2}
        # Mirroring x negates rotations about y and z (M R M with M = diag(−1, 1, 1)).
        mirrored = {"x": 1.0, "y": -1.0, "z": -1.0} if self.side == "left" else None
        matrix = np.zeros((len(self.dofs), len(names) * 3))
        for i, dof in enumerate(self.dofs):
            sign = dof.sign * (mirrored[dof.axis] if mirrored else 1.0)
            matrix[i, names.index(dof.joint) * 3 + column[dof.axis]] = sign
        rest_q = np.zeros((len(names), 4))
        rest_q[:, 3] = 1.0
        for name, rotation in rest.items():
            rest_q[names.index(name)] = Rotation.from_matrix(
                self.mirror @ rotation @ self.mirror
            ).as_quat()
        return matrix, rest_q

    def local_quaternions(self, dofs_rad: np.ndarray) -> np.ndarray:
        """Return each joint's local rotation, (..., n_dofs) → (..., n_joints, 4) quaternions.

        A joint's rotation is its rest rotation followed by its DOFs as ZXY Euler angles.
        """
        dofs_rad = np.asarray(dofs_rad, dtype=np.float64)
        matrix, rest_q = self._angle_map
        angles = (dofs_rad @ matrix).reshape(*dofs_rad.shape[:-1], len(rest_q), 3)
        return quat_multiply(rest_q, quat_from_euler(angles, "ZXY"))

    def pose(self, dofs_rad: np.ndarray) -> Pose:
        """Return global joint transforms for DOF vectors, shape (n_frames, n_dofs) or (n_dofs,)."""
        dofs_rad = np.atleast_2d(dofs_rad)
        skeleton = self.skeleton
        translations = np.broadcast_to(
            skeleton.offsets * skeleton.metres_per_unit, (dofs_rad.shape[0], len(skeleton), 3)
        )
        return forward_kinematics_arrays(skeleton, self.local_quaternions(dofs_rad), translations)

    def channel_values(self, dofs_rad: np.ndarray) -> np.ndarray:
        """Return BVH channel values (degrees, ZXY per joint) for DOF vectors (n_frames, n_dofs)."""
        quaternions = self.local_quaternions(np.atleast_2d(dofs_rad))
        with_channels = [i for i, joint in enumerate(self.skeleton.joints) if joint.channels]
        angles = Rotation.from_quat(quaternions[:, with_channels].reshape(-1, 4)).as_euler(
            "ZXY", degrees=True
        )
        return angles.reshape(quaternions.shape[0], -1)
