"""Hand curves in and out: a motion's finger rotation curves in degrees, and back.

A hand motion is the engine's hand model (a hand BVH written by ``python -m synthesis
spell --export-bvh``), its upper body (both hands: seed 002's 50 curves), or a captured
``.pose`` file (its hands fitted as ``python -m synthesis capture`` does). The curves
are the digits' DOFs, named as seed 002 names them (``riRingMCPy``); the forearm and
wrist are left as they are.
"""

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from synthesis.hands.reduction import apply_reduction, find_reduction
from synthesis.rigs.body import BodyModel
from synthesis.rigs.hand import HandModel
from synthesis.skeleton.retime import resample_curves

# The hand model's DOFs that place the hand rather than shape it.
PLACEMENT = (
    "forearm_tilt_side",
    "forearm_tilt_forward",
    "forearm_twist",
    "wrist_deviation",
    "wrist_flexion",
)
ANALYSIS_RATE_HZ = 30.0


class HandMotionError(ValueError):
    """A file that holds no hand motion the reduction can read."""


@dataclass(frozen=True, eq=False)
class HandMotion:
    """A rig's DOFs over frames, and which of them are the hands' digit curves.

    *dofs_rad* (n_frames, n_dofs) of *rig* at *rate_hz*; *columns* the digit DOFs'
    indices; *names* their seed 002 names.
    """

    rig: object
    dofs_rad: np.ndarray
    rate_hz: float
    columns: np.ndarray
    names: tuple[str, ...]

    def curves_deg(self) -> np.ndarray:
        """Return the digit curves in degrees (n_frames, n_curves)."""
        return np.degrees(self.dofs_rad[:, self.columns])

    def analysis_curves_deg(self, rate_hz: float = ANALYSIS_RATE_HZ) -> np.ndarray:
        """Return the digit curves resampled to *rate_hz* (seed 002 works at 30 fps)."""
        return resample_curves(self.curves_deg(), self.rate_hz, rate_hz)

    def with_curves_deg(self, curves_deg: np.ndarray) -> "HandMotion":
        """Return the motion with its digit curves replaced (degrees, at its own rate)."""
        dofs = np.array(self.dofs_rad)
        dofs[:, self.columns] = np.radians(curves_deg)
        return HandMotion(self.rig, dofs, self.rate_hz, self.columns, self.names)

    def as_bvh_motion(self):
        """Return the motion as a BVH-ready Motion of its rig."""
        return self.rig.as_motion(self.dofs_rad, self.rate_hz)


def digit_columns(rig) -> tuple[np.ndarray, tuple[str, ...]]:
    """Return the digit DOFs of *rig* (a hand or the body) and their seed 002 names."""
    digits = [d for d in HandModel("right").dofs if d.name not in PLACEMENT]
    if isinstance(rig, HandModel):
        prefix = "ri" if rig.side == "right" else "le"
        found = [(rig.dof_names.index(d.name), prefix + d.literature[2:]) for d in digits]
    else:
        found = [
            (rig.dof_names.index(f"{side}_{d.name}"), short + d.literature[2:])
            for side, short in (("right", "ri"), ("left", "le"))
            for d in digits
        ]
    columns, names = zip(*found, strict=True)
    return np.array(columns), tuple(names)


def from_dofs(rig, dofs_rad: np.ndarray, rate_hz: float) -> HandMotion:
    """Return the hand motion of a rig's DOF vectors."""
    columns, names = digit_columns(rig)
    return HandMotion(rig, np.asarray(dofs_rad, float), rate_hz, columns, names)


def read_hand_motion(path: str | Path, side: str = "right") -> HandMotion:
    """Return the hand motion in a hand or body BVH of the engine, or a .pose file."""
    path = Path(path)
    suffix = path.suffix.lower()
    if suffix == ".pose":
        from synthesis.capture import captured_hand, read_pose

        try:
            hand = captured_hand(read_pose(path), side)
        except (ValueError, OSError) as error:
            raise HandMotionError(f"{path}: {error}") from None
        return from_dofs(HandModel(side), hand.fit.dofs_rad, hand.motion.rate_hz)
    if suffix != ".bvh":
        raise HandMotionError(f"{path}: a hand motion is a .bvh or a .pose file.")
    from synthesis.skeleton.bvh import BvhError, read_bvh

    try:
        motion = read_bvh(path)
    except (BvhError, OSError) as error:
        raise HandMotionError(f"{path}: {error}") from None
    for rig in (HandModel(side), BodyModel(side)):
        try:
            return from_dofs(rig, rig.dofs_from_motion(motion), motion.rate_hz)
        except ValueError:
            continue
    raise HandMotionError(
        f"{path}: not a BVH of the engine's hand or body (python -m "
        "synthesis spell --export-bvh writes one); retarget it first."
    )


def reduce_motion(motion: HandMotion, range_deg: float, rmsd: float | None):
    """Return *motion* with seed 002's reduction applied, and the reduction.

    The relations are found on the curves at 30 fps, as the seed analysed them, and
    applied to the motion at its own rate.
    """
    reduction = find_reduction(motion.analysis_curves_deg(), motion.names, range_deg, rmsd)
    return motion.with_curves_deg(apply_reduction(motion.curves_deg(), reduction)), reduction
