"""Fingerspelling timing: per-letter holds and per-pair transitions, and the models that
predict them (spec 02; seed 000 ch. 4)."""

from synthesis.timing.constant import constant_timing, normalized_constant_timing
from synthesis.timing.word import TimingError, WordTiming

__all__ = ["TimingError", "WordTiming", "constant_timing", "normalized_constant_timing"]
