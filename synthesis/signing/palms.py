"""Check the palms of a sentence's keys against their signs' definitions.

A sign's key says which way the palm faces (``palm: forward``, ``in``, a vector); the arm
is solved by IK toward it, within the wrist's and forearm's limits. This reports, per
key and hand, how far the solved palm faces from the one asked for, so that a sign the
body cannot turn as written is found (issue 36: letters seen edge-on).
"""

from dataclasses import dataclass

import numpy as np

from synthesis.rigs.body import BodyModel
from synthesis.signing.sentence import TORSO_TO_WORLD, KeySolver, parse_glosses, timeline
from synthesis.signing.signs import SignLibrary, default_library
from synthesis.signing.spine import SpineParams
from synthesis.skeleton.rotations import quat_to_matrix


@dataclass(frozen=True)
class PalmError:
    """One hand in one key: the key's time (ms), the hand, and the angle (degrees)
    between the palm it asked for and the palm the solved arm shows."""

    ms: float
    side: str
    angle_deg: float


def palm_errors(text: str, library: SignLibrary | None = None,
                spine: bool = True) -> list[PalmError]:  # fmt: skip
    """Return every key's palm error for the glosses of *text* (right-handed)."""
    library = library or default_library()
    keys, _ = timeline(parse_glosses(text), library)
    solver = KeySolver(BodyModel("right"), SpineParams())
    automated = solver.automated(keys) if spine else np.zeros((len(keys), len(solver.names)))
    pose = solver.body.pose(solver.keys(keys, automated))
    errors = []
    for side in ("right", "left"):
        wrist = solver.body.skeleton.index(f"{side}_wrist")
        normals = quat_to_matrix(pose.quaternions[:, wrist])[:, :, 2]
        for key, normal in zip(keys, normals, strict=True):
            wanted = TORSO_TO_WORLD @ key.hands[side].palm
            cosine = np.clip(normal @ wanted / np.linalg.norm(wanted), -1.0, 1.0)
            errors.append(PalmError(key.ms, side, float(np.degrees(np.arccos(cosine)))))
    return errors
