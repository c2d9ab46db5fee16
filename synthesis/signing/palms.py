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
from synthesis.signing.sentence import TORSO_TO_WORLD, KeySolver, parse_glosses, timeline
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


def key_misses(text: str, library: SignLibrary | None = None,
               spine: bool = True) -> list[KeyMiss]:  # fmt: skip
    """Return every key's palm and wrist misses for the glosses of *text* (right-handed)."""
    keys, _ = timeline(parse_glosses(text), library or default_library())
    solver = KeySolver(BodyModel("right"), SpineParams())
    automated = solver.automated(keys) if spine else np.zeros((len(keys), len(solver.names)))
    pose = solver.body.pose(solver.keys(keys, automated))
    misses = []
    for side in ("right", "left"):
        wrist = solver.body.skeleton.index(f"{side}_wrist")
        normals = quat_to_matrix(pose.quaternions[:, wrist])[:, :, 2]
        for key, normal, place in zip(keys, normals, pose.positions_m[:, wrist], strict=True):
            wanted = TORSO_TO_WORLD @ key.hands[side].palm
            cosine = np.clip(normal @ wanted / np.linalg.norm(wanted), -1.0, 1.0)
            miss = np.linalg.norm(place - solver.world(key.hands[side].at_m))
            misses.append(KeyMiss(key.ms, side, float(np.degrees(np.arccos(cosine))),
                                  float(miss)))  # fmt: skip
    return misses
