"""Build the demo studies as study definitions (the format of :mod:`studyplatform.exchange`)."""

from studyplatform.demo.fingerspelling import fingerspelling_timing_study
from studyplatform.demo.spine import spine_study

DEMO_STUDIES = (fingerspelling_timing_study, spine_study)

__all__ = ["DEMO_STUDIES", "fingerspelling_timing_study", "spine_study"]
