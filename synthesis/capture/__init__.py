"""Human motion in: ``.pose`` landmark files, the hand model fitted to them, and
markerless capture of hands from video (synthesis.capture.video, MediaPipe, imported lazily)."""

from synthesis.capture.features import handshape_features, nearest_handshape
from synthesis.capture.handfit import FitError, HandFit, calibrate_bones, calibrate_scale, fit_hand
from synthesis.capture.lexicon import LexiconMissing, human_letter_files
from synthesis.capture.posefile import (
    HAND_COMPONENTS,
    PoseFileError,
    PoseRecording,
    format_pose,
    from_hand_motion,
    parse_pose,
    read_pose,
    write_pose,
)
from synthesis.capture.recording import CapturedHand, captured_hand
from synthesis.capture.report import write_report

__all__ = [
    "HAND_COMPONENTS",
    "CapturedHand",
    "FitError",
    "HandFit",
    "LexiconMissing",
    "PoseFileError",
    "PoseRecording",
    "calibrate_bones",
    "calibrate_scale",
    "captured_hand",
    "fit_hand",
    "format_pose",
    "from_hand_motion",
    "handshape_features",
    "human_letter_files",
    "nearest_handshape",
    "parse_pose",
    "read_pose",
    "write_pose",
    "write_report",
]
