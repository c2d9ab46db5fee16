"""Check stimuli before participants see them: joint speeds against the keyed motion,
hands in the frame and large enough to read, hands through the body, the face hidden.

Depends on :mod:`synthesis.techniques` (to make a clip's motion and its reference);
nothing below it imports this package.
"""

from synthesis.quality.clip import check_request, keyed_reference
from synthesis.quality.report import (
    CHECKS,
    FACE_HIDDEN_S,
    FACE_HIDDEN_SHARE,
    HAND_MIN_PX,
    PENETRATION_M,
    SPEED_FACTOR,
    ClipQuality,
    Finding,
    check_motion,
)

__all__ = [
    "CHECKS",
    "FACE_HIDDEN_S",
    "FACE_HIDDEN_SHARE",
    "HAND_MIN_PX",
    "PENETRATION_M",
    "SPEED_FACTOR",
    "ClipQuality",
    "Finding",
    "check_motion",
    "check_request",
    "keyed_reference",
]
