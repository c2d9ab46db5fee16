"""Check a sentence's solved keys against their signs' definitions: palms and wrists.

A sign's key says which way the palm faces (``palm: forward``, ``in``, a vector) and
where the wrist is (``at``); the arm is solved by IK toward both, within the wrist's and
forearm's limits, and gives up position for turn where it cannot have both. This
reports, per key and hand, how far the solved palm faces from the one asked for and how
far the solved wrist is from its place, so that a sign the body cannot make as written is
found (issue 36: letters seen edge-on; BROTHER's hand 13 cm beside the forehead).
"""

from dataclasses import dataclass

import numpy as np

from synthesis.rigs.body import BodyModel
from synthesis.signing.keys import KeySolver
from synthesis.signing.sentence import parse_glosses, timeline
from synthesis.signing.signs import SignLibrary, default_library
from synthesis.signing.spine import SpineParams
from synthesis.skeleton.rotations import quat_to_matrix


@dataclass(frozen=True)
class KeyMiss:
    """One hand in one key: the key's time (ms), the hand, the angle (degrees) between
    the palm it asked for and the palm the solved arm shows, and the distance (m)
    between the wrist's place it asked for and where the solved arm puts it."""

    ms: float
    side: str
    angle_deg: float
    miss_m: float


def key_misses(text: str, library: SignLibrary | None = None, spine: bool = True) -> list[KeyMiss]:
    """Return every key's palm and wrist misses for the glosses of *text* (right-handed)."""
    keys, _ = timeline(parse_glosses(text), library or default_library())
    solver = KeySolver(BodyModel("right"), SpineParams())
    automated = solver.automated(keys) if spine else np.zeros((len(keys), len(solver.names)))
    pose = solver.body.pose(solver.keys(keys, automated))
    trunk = solver.trunks(keys)
    misses = []
    for side, (targets, palms, _) in solver.placed(keys, trunk, trunk + automated).items():
        wrist = solver.body.skeleton.index(f"{side}_wrist")
        normals = quat_to_matrix(pose.quaternions[:, wrist])[:, :, 2]
        solved = zip(keys, normals, pose.positions_m[:, wrist], targets, palms, strict=True)
        for key, normal, place, target, wanted in solved:
            cosine = np.clip(normal @ wanted / np.linalg.norm(wanted), -1.0, 1.0)
            miss = np.linalg.norm(place - target)
            misses.append(KeyMiss(key.ms, side, float(np.degrees(np.arccos(cosine))), float(miss)))
    return misses
