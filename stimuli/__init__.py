"""Turn a study design into the set of clips to render (pairs, counterbalancing, caching).

Depends on :mod:`synthesis` only; never on Django or :mod:`studyplatform`.
"""

from stimuli.clips import ClipError, ClipSpec, RenderedClip, engine_digest, render
from stimuli.design import (
    all_ordered_pairs,
    attention_checks,
    balanced_pair_assignment,
    latin_square,
    rotate_for_participant,
    shuffled,
)
from stimuli.manifest import Entry, generate, read_manifest, write_manifest
from stimuli.plan import Design, DesignError, DesignSpec, PlannedPage, plan_pages, summarize_pages
from stimuli.quality import checked, quality_file, stored_quality

__all__ = [
    "ClipError",
    "ClipSpec",
    "Design",
    "DesignError",
    "DesignSpec",
    "Entry",
    "PlannedPage",
    "RenderedClip",
    "all_ordered_pairs",
    "attention_checks",
    "balanced_pair_assignment",
    "checked",
    "engine_digest",
    "generate",
    "latin_square",
    "plan_pages",
    "quality_file",
    "read_manifest",
    "render",
    "rotate_for_participant",
    "shuffled",
    "stored_quality",
    "summarize_pages",
    "write_manifest",
]
