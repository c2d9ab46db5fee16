"""Expose the study platform's models."""

from studyplatform.models.avatars import Avatar
from studyplatform.models.design import AnswerOption, Block, Question, Trial, trial_question_kinds
from studyplatform.models.devices import KnownDevice
from studyplatform.models.items import Item
from studyplatform.models.participants import (
    Participant,
    PersonalAnswer,
    new_participant_token,
    new_randomization_seed,
)
from studyplatform.models.prompts import PARTICIPANT_FACING_FIELDS, AslVideo, SignedTemplate
from studyplatform.models.recordings import Recording
from studyplatform.models.responses import MediaEvent, Response
from studyplatform.models.scope import STUDY_PATHS
from studyplatform.models.stimuli import ClipUpload, Stimulus, UploadedClip
from studyplatform.models.studies import Condition, Study
from studyplatform.models.withdrawals import Withdrawal

__all__ = [
    "PARTICIPANT_FACING_FIELDS",
    "STUDY_PATHS",
    "AnswerOption",
    "AslVideo",
    "Avatar",
    "Block",
    "ClipUpload",
    "Condition",
    "Item",
    "KnownDevice",
    "MediaEvent",
    "Participant",
    "PersonalAnswer",
    "Question",
    "Recording",
    "Response",
    "SignedTemplate",
    "Stimulus",
    "Study",
    "Trial",
    "UploadedClip",
    "Withdrawal",
    "new_participant_token",
    "new_randomization_seed",
    "trial_question_kinds",
]
