"""The seven arm curves a transition is made of (seed 001 §3.3), per arm of the body rig.

Seed 001 stores shoulder rotation x/y/z, elbow rotation x and wrist rotation x/y/z for
each transition; on the engine's body these are the shoulder's flexion, abduction and
rotation, the elbow's flexion, and the forearm twist and the wrist's flexion and
deviation. Curves are angles in radians over frames.
"""

from collections.abc import Sequence

import numpy as np

ARM_CURVES = (
    "shoulder_flexion",
    "shoulder_abduction",
    "shoulder_rotation",
    "elbow_flexion",
    "forearm_twist",
    "wrist_flexion",
    "wrist_deviation",
)
# The seed's names for the curves, as its Table 5.1 and Appendix B print them.
SEED_NAMES = ("shoulder x", "shoulder y", "shoulder z", "elbow", "wrist x", "wrist y", "wrist z")
SIDES = ("right", "left")


def arm_columns(dof_names: Sequence[str], side: str) -> np.ndarray:
    """Return the columns of *side*'s seven arm curves in a motion with *dof_names*."""
    if side not in SIDES:
        raise ValueError(f"side must be 'right' or 'left', not {side!r}.")
    names = list(dof_names)
    missing = [c for c in ARM_CURVES if f"{side}_{c}" not in names]
    if missing:
        raise ValueError(f"The motion has no {side} arm curve {', '.join(missing)}.")
    return np.array([names.index(f"{side}_{c}") for c in ARM_CURVES])
