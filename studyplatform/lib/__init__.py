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
    "DesignSummary",
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
    "describe_identical",
    "describe_parameters",
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
