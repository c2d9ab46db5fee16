"""Reads the platform's views, admin and actions share: queries and derivations.

Writes live in :mod:`studyplatform.actions`; nothing here changes the database.
"""

from studyplatform.lib.media import files_in_use
from studyplatform.lib.participants import (
    TIME_LOW,
    PageRejected,
    clean_recruitment_params,
    closed_reason,
    completion_url,
    missing_answers,
    page_count,
    page_trial,
    time_left,
    unwatched_clips,
)
from studyplatform.lib.presentation import presented_conditions, schedule_entry
from studyplatform.lib.stimuli import (
    clip_spec,
    files_exist,
    needed_pairs,
    stimuli_progress,
    study_manifest,
)
from studyplatform.lib.techniques import (
    check_condition,
    check_item,
    check_parameters,
    condition_item_kinds,
    describe_condition,
    describe_parameters,
)

__all__ = [
    "TIME_LOW",
    "PageRejected",
    "check_condition",
    "check_item",
    "check_parameters",
    "clean_recruitment_params",
    "clip_spec",
    "closed_reason",
    "completion_url",
    "condition_item_kinds",
    "describe_condition",
    "describe_parameters",
    "files_exist",
    "files_in_use",
    "missing_answers",
    "needed_pairs",
    "page_count",
    "page_trial",
    "presented_conditions",
    "schedule_entry",
    "stimuli_progress",
    "study_manifest",
    "time_left",
    "unwatched_clips",
]
