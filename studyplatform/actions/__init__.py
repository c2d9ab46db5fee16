"""Write to the database: every change that touches several rows goes through here.

Each action is a ``do_<verb>_<noun>()`` function that runs in one transaction and
raises a ValidationError subclass naming the problem when its input is unacceptable,
leaving the database as it was.
"""

from studyplatform.actions.events import EventsRejected, do_log_media_events
from studyplatform.actions.participants import (
    PageRejected,
    clean_recruitment_params,
    closed_reason,
    completion_url,
    do_advance_participant,
    do_enroll_participant,
    do_go_back_participant,
    do_set_participant_language,
    page_count,
    page_trial,
    time_left,
)
from studyplatform.actions.responses import (
    Answer,
    AnswerRejected,
    do_save_response,
    presented_conditions,
    schedule_entry,
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
    "EventsRejected",
    "ImportResult",
    "PageRejected",
    "StudyImportError",
    "clean_recruitment_params",
    "closed_reason",
    "completion_url",
    "do_advance_participant",
    "do_duplicate_study",
    "do_enroll_participant",
    "do_go_back_participant",
    "do_import_study",
    "do_log_media_events",
    "do_save_response",
    "do_set_participant_language",
    "free_slug",
    "page_count",
    "page_trial",
    "presented_conditions",
    "schedule_entry",
    "time_left",
]
