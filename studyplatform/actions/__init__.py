"""Write to the database: every change that touches several rows goes through here.

Each action is a ``do_<verb>_<noun>()`` function that runs in one transaction and
raises a ValidationError subclass naming the problem when its input is unacceptable,
leaving the database as it was. Reads live in :mod:`studyplatform.lib`.
"""

from studyplatform.actions.events import EventsRejected, do_log_media_events
from studyplatform.actions.participants import (
    do_advance_participant,
    do_enroll_participant,
    do_go_back_participant,
    do_set_participant_language,
)
from studyplatform.actions.privacy import (
    RetentionResult,
    do_apply_retention,
    do_withdraw_participant,
)
from studyplatform.actions.prompts import do_attach_asl_video
from studyplatform.actions.recordings import (
    RecordingRejected,
    do_attach_recording,
    do_delete_recordings,
    do_fail_recording,
    do_finish_recording,
    do_report_capture_progress,
)
from studyplatform.actions.responses import do_save_page_answers, do_save_response
from studyplatform.actions.reviews import do_review_participants
from studyplatform.actions.stimuli import (
    GenerateOptions,
    GenerationResult,
    RerenderRefused,
    do_fail_stimulus,
    do_generate_stimuli,
    do_record_rendered_stimulus,
    do_retry_stimuli,
    do_start_rendering,
)
from studyplatform.actions.studies import (
    ImportResult,
    StudyImportError,
    do_duplicate_study,
    do_import_study,
)
from studyplatform.actions.uploads import (
    UploadOffsetMismatch,
    UploadRejected,
    do_append_signed_answer_chunk,
)
from studyplatform.actions.versions import do_create_study_version
from studyplatform.lib.participants import PageRejected
from studyplatform.questions import Answer, AnswerRejected

__all__ = [
    "Answer",
    "AnswerRejected",
    "EventsRejected",
    "GenerateOptions",
    "GenerationResult",
    "ImportResult",
    "PageRejected",
    "RecordingRejected",
    "RerenderRefused",
    "RetentionResult",
    "StudyImportError",
    "UploadOffsetMismatch",
    "UploadRejected",
    "do_advance_participant",
    "do_append_signed_answer_chunk",
    "do_apply_retention",
    "do_attach_asl_video",
    "do_attach_recording",
    "do_create_study_version",
    "do_delete_recordings",
    "do_duplicate_study",
    "do_enroll_participant",
    "do_fail_recording",
    "do_fail_stimulus",
    "do_finish_recording",
    "do_generate_stimuli",
    "do_go_back_participant",
    "do_import_study",
    "do_log_media_events",
    "do_record_rendered_stimulus",
    "do_report_capture_progress",
    "do_retry_stimuli",
    "do_review_participants",
    "do_save_page_answers",
    "do_save_response",
    "do_set_participant_language",
    "do_start_rendering",
    "do_withdraw_participant",
]
