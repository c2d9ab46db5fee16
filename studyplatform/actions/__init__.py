"""Write to the database: every change that touches several rows goes through here.

Each action is a ``do_<verb>_<noun>()`` function that runs in one transaction and
raises a ValidationError subclass naming the problem when its input is unacceptable,
leaving the database as it was.
"""

from studyplatform.actions.participants import clean_recruitment_params, do_enroll_participant
from studyplatform.actions.responses import (
    Answer,
    AnswerRejected,
    do_save_response,
    presented_conditions,
)
from studyplatform.actions.studies import (
    ImportResult,
    StudyImportError,
    do_duplicate_study,
    do_import_study,
    free_slug,
)

__all__ = [
    "Answer",
    "AnswerRejected",
    "ImportResult",
    "StudyImportError",
    "clean_recruitment_params",
    "do_duplicate_study",
    "do_enroll_participant",
    "do_import_study",
    "do_save_response",
    "free_slug",
    "presented_conditions",
]
