"""Fingerspelling timing: per-letter holds and per-pair transitions, and the models that
predict them (spec 02; seed 000 ch. 4)."""

from synthesis.fingerspelling.word_timing import TimingError, WordTiming
from synthesis.timing.bayes import HoldClassifier, LeaveOneOut
from synthesis.timing.constant import constant_timing, normalized_constant_timing
from synthesis.timing.defaults import published_model
from synthesis.timing.extraction import Extraction, ExtractionError, extract
from synthesis.timing.features import DEFAULT_FEATURES, FEATURES, letter_features
from synthesis.timing.simulate import CaptureNoise, sample_timing, simulate_recording
from synthesis.timing.transitions import (
    SPACES,
    TransitionModel,
    joint_differences,
    letter_distance,
    pose_distance,
)
from synthesis.timing.variable import VariableModel

__all__ = [
    "DEFAULT_FEATURES",
    "FEATURES",
    "SPACES",
    "CaptureNoise",
    "Extraction",
    "ExtractionError",
    "HoldClassifier",
    "LeaveOneOut",
    "TimingError",
    "TransitionModel",
    "VariableModel",
    "WordTiming",
    "constant_timing",
    "extract",
    "joint_differences",
    "letter_distance",
    "letter_features",
    "normalized_constant_timing",
    "pose_distance",
    "published_model",
    "sample_timing",
    "simulate_recording",
]
