"""Participant-facing and public views of the platform."""

from studyplatform.views.home import favicon, home
from studyplatform.views.language import javascript_catalog
from studyplatform.views.media import media, participant_answer_video, private_media, uploaded_clip
from studyplatform.views.participate import (
    done,
    log_events,
    page,
    resume,
    save_answer,
    set_language,
    study_welcome,
)
from studyplatform.views.signed import upload_signed_answer
from studyplatform.views.withdraw import withdraw

__all__ = [
    "done",
    "favicon",
    "home",
    "javascript_catalog",
    "log_events",
    "media",
    "page",
    "participant_answer_video",
    "private_media",
    "resume",
    "save_answer",
    "set_language",
    "study_welcome",
    "upload_signed_answer",
    "uploaded_clip",
    "withdraw",
]
