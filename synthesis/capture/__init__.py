"""Human motion in: ``.pose`` landmark files, the hand model fitted to them, and
markerless capture of hands from video (synthesis.capture.video, MediaPipe, imported lazily)."""

from synthesis.capture.handfit import FitError, HandFit, calibrate_scale, fit_hand
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
from synthesis.capture.recording import CapturedHand, captured_hand, write_report

__all__ = [
    "HAND_COMPONENTS",
    "CapturedHand",
    "FitError",
    "HandFit",
    "PoseFileError",
    "PoseRecording",
    "calibrate_scale",
    "captured_hand",
    "fit_hand",
    "format_pose",
    "from_hand_motion",
    "parse_pose",
    "read_pose",
    "write_pose",
    "write_report",
]
