"""Reads the platform's views, admin and actions share: queries and derivations.

Writes live in :mod:`studyplatform.actions`; nothing here changes the database.
"""

from studyplatform.lib.design import DesignSummary, summarize_design
from studyplatform.lib.media import files_in_use
from studyplatform.lib.participants import (
    TIME_LOW,
    PageRejected,
    clean_recruitment_params,
    closed_reason,
    completion_url,
    device_problem,
    missing_answers,
    page_count,
    page_trial,
    participant_by_token,
    time_left,
    unwatched_clips,
)
from studyplatform.lib.presentation import presented_conditions, schedule_entry
from studyplatform.lib.quality import device_of, page_orders, quality_cells, study_quality
from studyplatform.lib.stimuli import (
    clip_spec,
    describe_identical,
    files_exist,
    identical_clips,
    needed_pairs,
    stimuli_progress,
    study_manifest,
)

__all__ = [
    "TIME_LOW",
    "DesignSummary",
    "PageRejected",
    "clean_recruitment_params",
    "clip_spec",
    "closed_reason",
    "completion_url",
    "describe_identical",
    "device_of",
    "device_problem",
    "files_exist",
    "files_in_use",
    "identical_clips",
    "missing_answers",
    "needed_pairs",
    "page_count",
    "page_orders",
    "page_trial",
    "participant_by_token",
    "presented_conditions",
    "quality_cells",
    "schedule_entry",
    "stimuli_progress",
    "study_manifest",
    "study_quality",
    "summarize_design",
    "time_left",
    "unwatched_clips",
]
