"""Tell the fist letters apart as ASL describes them: where the thumb lies.

A, E, M, N, S and T close the four fingers and differ by the thumb (the alphabet's own
descriptions in ``synthesis/data/alphabets/asl.yaml``, after the standard ASL manual
alphabet): **A** beside the index; **S** across the front of the index and middle
fingers; **T** poking up between the index and middle; **E** under the fingertips bent
down onto it; **N** tucked under the index and middle, its tip between middle and ring;
**M** tucked under the index, middle and ring, its tip between ring and pinky.
:func:`thumb_place` measures the thumb tip in the palm's frame and :func:`fist_letter`
names the letter that placement makes (issue 52: renders of M and N looked alike, T
like A). The limits sit midway between the letters' own placements.
"""

from dataclasses import dataclass

import numpy as np

FIST_LETTERS = ("A", "E", "M", "N", "S", "T")
_FINGERS = ("index", "middle", "ring", "pinky")


@dataclass(frozen=True)
class ThumbPlace:
    """The thumb tip in the palm's frame, in knuckle widths (index to pinky knuckle).

    *across* is 0 on the index knuckle's line and 1 on the pinky's; *along* runs from
    the knuckles toward the fingertips; *out* is how far the tip lies in front of the
    index and middle fingers' middle phalanges (positive: over them, on the palm side
    of a fist, where a viewer sees it). *to_tips* is the mean distance from the index
    and middle fingertips to the thumb's last bone.
    """

    across: float
    along: float
    out: float
    to_tips: float


def _segment_distance(point: np.ndarray, start: np.ndarray, end: np.ndarray) -> float:
    """Return the distance from *point* to the segment *start*–*end*."""
    axis = end - start
    t = np.clip((point - start) @ axis / max(axis @ axis, 1e-12), 0.0, 1.0)
    return float(np.linalg.norm(point - (start + t * axis)))


def thumb_place(joints: dict[str, np.ndarray]) -> ThumbPlace:
    """Return where the thumb tip lies, from joint positions (m) by the hand model's names."""
    origin, pinky = joints["index_mcp"], joints["pinky_mcp"]
    width = float(np.linalg.norm(pinky - origin))
    across = (pinky - origin) / width
    along = (origin + pinky) / 2 - joints["wrist"]
    along = along - (along @ across) * across
    along /= np.linalg.norm(along)
    # The palm side: the way the curled fingers' middle phalanges go from the knuckles.
    palm = np.cross(across, along)
    middles = [(joints[f"{f}_pip"] + joints[f"{f}_dip"]) / 2 for f in _FINGERS[:2]]
    if np.mean([(m - origin) @ palm for m in middles]) > 0:
        palm = -palm
    tip = joints["thumb_tip"] - origin
    front = -np.mean([(m - origin) @ palm for m in middles])
    to_tips = np.mean(
        [
            _segment_distance(joints[f"{f}_tip"], joints["thumb_ip"], joints["thumb_tip"])
            for f in _FINGERS[:2]
        ]
    )
    return ThumbPlace(
        float(tip @ across / width),
        float(tip @ along / width),
        float((-(tip @ palm) - front) / width),
        float(to_tips / width),
    )


def fist_letter(place: ThumbPlace) -> str:
    """Return the fist letter (:data:`FIST_LETTERS`) the thumb's placement makes."""
    if place.out < 0.1:  # beside or under the fingers
        if place.across < 0.2:
            return "A"
        return "M" if place.across > 0.77 else "N"
    if place.to_tips < 0.45 and place.along < 0.0:
        return "E"
    return "T" if place.across < 0.38 and place.along > 0.1 else "S"
