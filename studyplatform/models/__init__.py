"""Expose the study platform's models."""

from studyplatform.models.design import TRIAL_QUESTION_KINDS, AnswerOption, Block, Question, Trial
from studyplatform.models.participants import (
    Participant,
    PersonalAnswer,
    new_participant_token,
    new_randomization_seed,
)
from studyplatform.models.prompts import PARTICIPANT_FACING_FIELDS, AslVideo
from studyplatform.models.responses import MediaEvent, Response
from studyplatform.models.scope import STUDY_PATHS
from studyplatform.models.stimuli import Stimulus
from studyplatform.models.studies import Condition, Item, Study

__all__ = [
    "PARTICIPANT_FACING_FIELDS",
    "STUDY_PATHS",
    "TRIAL_QUESTION_KINDS",
    "AnswerOption",
    "AslVideo",
    "Block",
    "Condition",
    "Item",
    "MediaEvent",
    "Participant",
    "PersonalAnswer",
    "Question",
    "Response",
    "Stimulus",
    "Study",
    "Trial",
    "new_participant_token",
    "new_randomization_seed",
]
