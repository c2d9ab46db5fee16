"""Build the demo studies as study definitions (the format of :mod:`studyplatform.lib.exchange`)."""

from studyplatform.demo.alphabet import alphabet_legibility_study, attach_human_letters
from studyplatform.demo.fingerspelling import fingerspelling_timing_study
from studyplatform.demo.hands import hands_study
from studyplatform.demo.signed import sign_prompts
from studyplatform.demo.spine import spine_study
from studyplatform.demo.transitions import transitions_study

DEMO_STUDIES = (
    fingerspelling_timing_study,
    spine_study,
    alphabet_legibility_study,
    transitions_study,
    hands_study,
)
# What a demo study needs besides its definition, by slug: recordings to attach.
DEMO_SETUP = {"alphabet-legibility": attach_human_letters}
# What a demo study shows when its clips are rendered, by slug: avatar-signed prompts.
DEMO_SIGNED = {"spine-motion": sign_prompts}

__all__ = [
    "DEMO_SETUP",
    "DEMO_SIGNED",
    "DEMO_STUDIES",
    "alphabet_legibility_study",
    "attach_human_letters",
    "fingerspelling_timing_study",
    "hands_study",
    "sign_prompts",
    "spine_study",
    "transitions_study",
]
