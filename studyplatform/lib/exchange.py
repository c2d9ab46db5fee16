"""Serialize a complete study definition to plain JSON data, and read it back.

The format is versioned (``format``/``version`` keys) and refers to objects by their
keys, never by database ids, so a file moves between installations. Stimuli are not
part of a definition: they are rendered again from it. ASL prompt videos, each word's
recording in use and the clips of uploaded conditions are referenced by their media
file names.
:func:`studyplatform.actions.do_import_study` writes a definition to the database.
"""

from typing import Any

from studyplatform.lib.recordings import current_recording
from studyplatform.models import Study, UploadedClip

FORMAT = "signstudy.study"
VERSION = 1

STUDY_FIELDS = (
    "slug",
    "title",
    "description",
    "status",
    "language",
    "follow_browser_language",
    "sign_language",
    "manual_alphabet",
    "clip_width",
    "clip_height",
    "phone_clips_side_by_side",
    "asl_first",
    "allow_english_only",
    "consent_text",
    "consent_mode",
    "thank_you_text",
    "completion_code",
    "redirect_url",
    "allowed_devices",
    "one_sitting",
    "shared_computer",
    "time_limit_minutes",
    "target_n",
    "allow_back",
    "replay_limit",
    "require_full_view",
    "randomize_positions",
    "rotate_conditions",
    "personal_data_retention_days",
    "allow_identical_clips",
    "unique_completion_codes",
    "design",
)
CONDITION_FIELDS = (
    "key",
    "label",
    "description",
    "source",
    "is_simulated",
    "parameters",
    "position",
)
ITEM_FIELDS = ("key", "kind", "text", "target_text", "is_practice", "parameters", "position")
QUESTION_FIELDS = (
    "key",
    "kind",
    "text",
    "help_text",
    "required",
    "allow_no_difference",
    "no_difference_label",
    "allow_signed_answer",
    "is_personal",
    "min_value",
    "max_value",
    "position",
)
OPTION_FIELDS = ("value", "label", "position")
BLOCK_FIELDS = ("key", "kind", "title", "intro_text", "randomize_order", "position")
TRIAL_FIELDS = (
    "key",
    "kind",
    "title",
    "text",
    "is_attention_check",
    "expected_answer",
    "position",
)
# Foreign keys of a trial, exported as the key of the object they point to.
TRIAL_REFERENCES = ("block", "item", "condition_a", "condition_b")
ASL_VIDEO_FIELDS = ("field_name", "transcript", "credit")
RECORDING_FIELDS = ("mirrored", "one_hand", "quality", "sha256")
RECORDING_FILES = ("upload", "motion", "sheet")
UPLOAD_FIELDS = (
    "original_name",
    "source_sha256",
    "sha256",
    "source_codec",
    "converted",
    "duration_ms",
    "frame_count",
    "frame_rate",
    "width",
    "height",
    "size_bytes",
)
UPLOAD_FILES = ("video", "poster")
# What each model of a definition exports: its fields, references and files.
EXPORTED = {
    "Study": STUDY_FIELDS,
    "Condition": CONDITION_FIELDS,
    "Item": ITEM_FIELDS,
    "Question": QUESTION_FIELDS,
    "AnswerOption": OPTION_FIELDS,
    "Block": BLOCK_FIELDS,
    "Trial": (*TRIAL_FIELDS, *TRIAL_REFERENCES, "questions"),
    "AslVideo": (*ASL_VIDEO_FIELDS, "video", "poster"),
    "Recording": (*RECORDING_FIELDS, *RECORDING_FILES),
    "UploadedClip": (*UPLOAD_FIELDS, *UPLOAD_FILES),
}
# Fields a definition leaves out on purpose, with why (the system check
# studyplatform.E004 fails on a field neither exported nor listed here).
LEFT_OUT = {
    "Study": {
        "owner": "whoever imports the file owns the study",
        "version": "a copy starts its own history (do_create_study_version numbers it)",
        "previous_version": "as version; ids never leave an installation",
        "created_at": "set when the study is made",
        "updated_at": "set when the study is saved",
        "signed_templates": "a researcher's own library; a copy keeps those its owner may use",
    },
    "Condition": {
        "study": "the definition is the study's",
        "avatar": "a researcher's own library (as signed templates): a copy films with the "
        "built-in signer unless its owner attaches an avatar of theirs",
    },
    "Item": {"study": "the definition is the study's"},
    "Question": {"study": "the definition is the study's"},
    "AnswerOption": {"question": "options are nested in their question"},
    "Block": {"study": "the definition is the study's"},
    "Trial": {"study": "the definition is the study's"},
    "AslVideo": {
        "content_type": "exported as the prompt's target (kind and key)",
        "object_id": "as content_type",
        "created_at": "set when the video is attached",
    },
    "Recording": {
        "item": "exported as the item's key",
        "status": "an imported recording is ready",
        "progress_percent": "as status",
        "error": "only ready recordings are exported",
        "created_at": "set when the recording is imported",
    },
    "UploadedClip": {
        "condition": "exported as the condition's key",
        "item": "exported as the item's key",
        "uploaded_at": "set when the clip is imported",
    },
}


def _values(obj: Any, fields: tuple[str, ...]) -> dict[str, Any]:
    return {name: getattr(obj, name) for name in fields}


def _asl_target(video) -> list[str | int | None]:
    """Name an ASL video's target as [model, key] (key None for the study itself)."""
    target = video.target
    model = video.content_type.model
    if model == "study":
        return [model, None]
    if model == "answeroption":
        return [model, f"{target.question.key}:{target.value}"]
    return [model, target.key]


def study_asl_videos(study: Study, questions=None) -> list:
    """Return the ASL videos of *study* and of its blocks, trials, questions and options."""
    if questions is None:
        questions = list(study.questions.prefetch_related("options"))
    asl_videos = list(study.asl_videos.all())
    for related in (study.blocks.all(), study.trials.all(), questions):
        for obj in related:
            asl_videos.extend(obj.asl_videos.all())
    for question in questions:
        for option in question.options.all():
            asl_videos.extend(option.asl_videos.all())
    return asl_videos


def _trial(trial, question_order: dict[str, int]) -> dict[str, Any]:
    """Return one trial's definition: its fields, what it refers to by key, its questions."""
    return {
        **_values(trial, TRIAL_FIELDS),
        **{
            ref: (getattr(trial, ref).key if getattr(trial, ref) is not None else None)
            for ref in TRIAL_REFERENCES
        },
        "questions": sorted((q.key for q in trial.questions.all()), key=question_order.__getitem__),
    }


def export_study(study: Study) -> dict[str, Any]:
    """Return the complete definition of *study* as JSON-compatible data."""
    questions = list(study.questions.prefetch_related("options"))
    trials = study.trials.select_related("block", "item", "condition_a", "condition_b")
    trials = trials.prefetch_related("questions")
    question_order = {q.key: index for index, q in enumerate(questions)}

    asl_videos = study_asl_videos(study, questions)

    items = list(study.items.all())
    recordings = [(item, current_recording(item)) for item in items]
    return {
        "format": FORMAT,
        "version": VERSION,
        "study": _values(study, STUDY_FIELDS),
        "conditions": [_values(c, CONDITION_FIELDS) for c in study.conditions.all()],
        "items": [_values(i, ITEM_FIELDS) for i in items],
        "questions": [
            {
                **_values(q, QUESTION_FIELDS),
                "options": [_values(o, OPTION_FIELDS) for o in q.options.all()],
            }
            for q in questions
        ],
        "blocks": [_values(b, BLOCK_FIELDS) for b in study.blocks.all()],
        "trials": [_trial(t, question_order) for t in trials],
        "asl_videos": [
            {
                "target": _asl_target(v),
                **_values(v, ASL_VIDEO_FIELDS),
                "video": v.video.name,
                "poster": v.poster.name,
            }
            for v in asl_videos
        ],
        "recordings": [
            {
                "item": item.key,
                **_values(recording, RECORDING_FIELDS),
                **{name: getattr(recording, name).name for name in RECORDING_FILES},
            }
            for item, recording in recordings
            if recording is not None
        ],
        "uploaded_clips": [
            {
                "condition": clip.condition.key,
                "item": clip.item.key,
                **_values(clip, UPLOAD_FIELDS),
                **{name: getattr(clip, name).name for name in UPLOAD_FILES},
            }
            for clip in UploadedClip.objects.filter(condition__study=study).select_related(
                "condition", "item"
            )
        ],
    }


def parameters_schema() -> dict:
    """Return the JSON Schema of condition and item ``parameters`` (from the technique registry).

    A condition's parameters may hold the techniques of any item kind of its study and the
    filming fields; an item's, those of its own kind. Saving and importing check the same
    rules with messages that name the field (studyplatform.lib.techniques).
    """
    from synthesis.techniques import REGISTRY, REQUEST_PARAMETERS

    filming = {p.name: p.schema() for p in REQUEST_PARAMETERS}
    by_kind = {
        kind: {**schema, "properties": {**schema["properties"], **filming}}
        for kind, schema in REGISTRY.schema().items()
    }
    return {
        "$schema": "https://json-schema.org/draft/2020-12/schema",
        "title": f"Parameters of conditions and items in a {FORMAT} definition (version {VERSION})",
        "description": "One object per item kind; a condition's parameters must fit the kind "
        "of every item of its study.",
        "$defs": by_kind,
        "anyOf": [{"$ref": f"#/$defs/{kind}"} for kind in by_kind],
    }
