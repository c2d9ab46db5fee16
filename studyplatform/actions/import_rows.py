"""Write a study definition's rows: one function per section, in dependency order.

Each row is checked like a form would check it (its fields, their kinds, the model's
``full_clean``); an error names the row (``trials[3].block``) and the import stops.
"""

from typing import Any

from django.core.exceptions import NON_FIELD_ERRORS, ValidationError
from django.db import models

from studyplatform.actions.import_media import (
    ASL_POSTER,
    ASL_VIDEO,
    RECORDING_KINDS,
    UPLOAD_KINDS,
    ImportedMedia,
    StudyImportError,
)
from studyplatform.lib import exchange
from studyplatform.lib.field_input import values_problems
from studyplatform.models import (
    AnswerOption,
    AslVideo,
    Block,
    Condition,
    Item,
    Question,
    Recording,
    Study,
    Trial,
    UploadedClip,
)


def pick(
    row: Any, fields: tuple[str, ...], where: str, model: type[models.Model] | None = None
) -> dict[str, Any]:
    """Return *row*'s values for *fields*, rejecting anything else it holds.

    With *model*, each value must be of the kind its field holds (lib.field_input).
    """
    if not isinstance(row, dict):
        raise StudyImportError(f"{where}: expected an object, got {type(row).__name__}.")
    unknown = sorted(set(row) - set(fields))
    if unknown:
        raise StudyImportError(f"{where}: unknown field(s) {', '.join(unknown)[:200]}.")
    values = {name: row[name] for name in fields if name in row}
    if model is not None:
        problems = values_problems(model, values)
        if problems:
            details = "; ".join(f"{name} {problem}" for name, problem in problems.items())
            raise StudyImportError(f"{where}: {details}.")
    return values


def _rows(data: dict[str, Any], name: str) -> list[Any]:
    rows = data.get(name, [])
    if not isinstance(rows, list):
        raise StudyImportError(f"{name}: expected a list.")
    return rows


def save_checked(obj: models.Model, where: str) -> None:
    """Validate *obj* like a form would, then save it; name the failing field on error.

    As ``full_clean``, except that foreign keys are not looked up in the database: an
    import sets each one to a row it holds (the study it made, a row it saved before,
    the importing user), never to an id from the file, and a lookup a key was a third
    of an import's queries. Unique constraints that include them are still checked.
    """
    foreign_keys = {
        field.name
        for field in obj._meta.concrete_fields
        if field.many_to_one and getattr(obj, field.attname) is not None
    }
    errors: dict = {}
    for check in (lambda: obj.clean_fields(exclude=foreign_keys), obj.clean):
        try:
            check()
        except ValidationError as error:
            errors = error.update_error_dict(errors)
    failed = set(errors) - {NON_FIELD_ERRORS}
    for check in (obj.validate_unique, obj.validate_constraints):
        try:
            check(exclude=failed)
        except ValidationError as error:
            errors = error.update_error_dict(errors)
    if errors:
        details = "; ".join(
            f"{field}: {' '.join(messages)}"
            for field, messages in ValidationError(errors).message_dict.items()
        )
        raise StudyImportError(f"{where}: {details}") from None
    obj.save()


def _lookup(table: dict[str, Any], key: Any, kind: str, where: str) -> Any:
    if key is None:
        return None
    try:
        return table[key]
    except (KeyError, TypeError):
        raise StudyImportError(f"{where}: unknown {kind} {key!r}.") from None


def _create_keyed(
    data: dict[str, Any],
    name: str,
    model: type[models.Model],
    fields: tuple[str, ...],
    study,
) -> dict[str, Any]:
    """Create the study's *name* rows of *model*; return them by key."""
    created = {}
    for index, row in enumerate(_rows(data, name)):
        where = f"{name}[{index}]"
        obj = model(study=study, **pick(row, fields, where, model))
        save_checked(obj, where)
        created[obj.key] = obj
    return created


def import_rows(data: dict, study: Study, media: ImportedMedia) -> list[str]:
    """Create every row of the definition *data* for *study*; return the warnings."""
    conditions = _create_keyed(data, "conditions", Condition, exchange.CONDITION_FIELDS, study)
    items = _create_keyed(data, "items", Item, exchange.ITEM_FIELDS, study)
    questions, options = _import_questions(data, study)
    blocks = _create_keyed(data, "blocks", Block, exchange.BLOCK_FIELDS, study)
    tables = {"block": blocks, "item": items, "condition_a": conditions, "condition_b": conditions}
    trials = _import_trials(data, study, tables, questions)
    targets = {"block": blocks, "trial": trials, "question": questions, "answeroption": options}
    warnings = _import_asl_videos(data, study, media, targets)
    warnings += _import_recordings(data, media, items)
    return warnings + _import_uploaded_clips(data, media, conditions, items)


def _import_questions(data: dict, study: Study) -> tuple[dict, dict]:
    """Create the questions with their options; return both by key ("question:value")."""
    questions: dict[str, Question] = {}
    options: dict[str, AnswerOption] = {}
    for index, row in enumerate(_rows(data, "questions")):
        where = f"questions[{index}]"
        values = pick(row, (*exchange.QUESTION_FIELDS, "options"), where, Question)
        option_rows = values.pop("options", [])
        question = Question(study=study, **values)
        save_checked(question, where)
        questions[question.key] = question
        if not isinstance(option_rows, list):
            raise StudyImportError(f"{where}.options: expected a list.")
        for option_index, option_row in enumerate(option_rows):
            option_where = f"{where}.options[{option_index}]"
            option = AnswerOption(
                question=question,
                **pick(option_row, exchange.OPTION_FIELDS, option_where, AnswerOption),
            )
            save_checked(option, option_where)
            options[f"{question.key}:{option.value}"] = option
    return questions, options


def _import_trials(data: dict, study: Study, tables: dict, questions: dict) -> dict:
    """Create the trials, each in its block with its clips and questions; return them."""
    trials: dict[str, Trial] = {}
    links = []
    for index, row in enumerate(_rows(data, "trials")):
        where = f"trials[{index}]"
        values = pick(
            row, (*exchange.TRIAL_FIELDS, *exchange.TRIAL_REFERENCES, "questions"), where, Trial
        )
        question_keys = values.pop("questions", [])
        for ref in exchange.TRIAL_REFERENCES:
            kind = "condition" if ref.startswith("condition") else ref
            values[ref] = _lookup(tables[ref], values.get(ref), kind, f"{where}.{ref}")
        if values["block"] is None:
            raise StudyImportError(f"{where}.block: every trial belongs to a block.")
        trial = Trial(study=study, **values)
        save_checked(trial, where)
        if not isinstance(question_keys, list):
            raise StudyImportError(f"{where}.questions: expected a list of question keys.")
        asked = [_lookup(questions, key, "question", f"{where}.questions") for key in question_keys]
        try:
            trial.check_questions(asked)
        except ValidationError as error:
            raise StudyImportError(f"{where}.questions: {' '.join(error.messages)}") from None
        links += [Trial.questions.through(trial=trial, question=q) for q in asked]
        trials[trial.key] = trial
    # One insert for every trial's questions (a set() a trial was four queries).
    Trial.questions.through.objects.bulk_create(links)
    return trials


def _import_asl_videos(data: dict, study: Study, media: ImportedMedia, targets: dict) -> list[str]:
    """Create the ASL videos of the study and its rows; return what was left out."""
    warnings = []
    for index, row in enumerate(_rows(data, "asl_videos")):
        where = f"asl_videos[{index}]"
        values = pick(
            row, (*exchange.ASL_VIDEO_FIELDS, "target", "video", "poster"), where, AslVideo
        )
        target = _asl_target(values.pop("target", None), study, targets, where)
        video_name = values.pop("video", "")
        video = media.resolve(video_name, "asl", ASL_VIDEO, "an ASL video's", f"{where}.video")
        poster = media.resolve(
            values.pop("poster", ""), "asl", ASL_POSTER, "an ASL video's", f"{where}.poster"
        )
        if not video:
            warnings.append(f"{where}: video file {video_name!r} is not in media; left out.")
            continue
        if poster is None:
            warnings.append(f"{where}: poster {row.get('poster')!r} is not in media; left out.")
        save_checked(AslVideo(target=target, video=video, poster=poster or "", **values), where)
    return warnings


def _asl_target(reference: Any, study: Study, targets: dict, where: str) -> models.Model:
    """Return the row an ASL video's ``[model, key]`` *reference* names."""
    if not (isinstance(reference, list) and len(reference) == 2):
        raise StudyImportError(f"{where}.target: expected [model, key].")
    model, key = reference
    if model == "study":
        return study
    if isinstance(model, str) and model in targets:
        return _lookup(targets[model], key, model, f"{where}.target")
    raise StudyImportError(f"{where}.target: unknown model {model!r}.")


def _import_recordings(data: dict, media: ImportedMedia, items: dict) -> list[str]:
    """Create the words' ready recordings whose files came; return what was left out."""
    warnings = []
    for index, row in enumerate(_rows(data, "recordings")):
        where = f"recordings[{index}]"
        values = pick(
            row, ("item", *exchange.RECORDING_FIELDS, *exchange.RECORDING_FILES), where, Recording
        )
        item = _lookup(items, values.pop("item", None), "item", f"{where}.item")
        if item is None or item.kind != Item.Kind.WORD:
            raise StudyImportError(
                f"{where}.item: recordings belong to words; "
                f"{getattr(item, 'key', None)!r} is not one."
            )
        named = {name: values.pop(name, "") or "" for name in exchange.RECORDING_FILES}
        found = {
            name: media.resolve(
                file_name, "recordings", RECORDING_KINDS[name], "a recording's", f"{where}.{name}"
            )
            for name, file_name in named.items()
        }
        missing = [name for name in ("upload", "motion") if not found[name]]
        if missing:
            warnings.append(
                f"{where}: {missing[0]} file {named[missing[0]]!r} of {item.key} "
                "is not in media; left out."
            )
            continue
        found["sheet"] = found["sheet"] or ""
        recording = Recording(
            item=item, status=Recording.Status.READY, progress_percent=100, **found, **values
        )
        save_checked(recording, where)
    return warnings


def _import_uploaded_clips(
    data: dict, media: ImportedMedia, conditions: dict, items: dict
) -> list[str]:
    """Create the uploaded conditions' clips whose files came; return what was left out."""
    warnings = []
    for index, row in enumerate(_rows(data, "uploaded_clips")):
        where = f"uploaded_clips[{index}]"
        values = pick(
            row,
            ("condition", "item", *exchange.UPLOAD_FIELDS, *exchange.UPLOAD_FILES),
            where,
            UploadedClip,
        )
        condition = _lookup(
            conditions, values.pop("condition", None), "condition", f"{where}.condition"
        )
        item = _lookup(items, values.pop("item", None), "item", f"{where}.item")
        if condition is None or item is None or not condition.is_uploaded:
            raise StudyImportError(
                f"{where}: clips belong to an item in a condition of uploaded clips."
            )
        named = {name: values.pop(name, "") or "" for name in exchange.UPLOAD_FILES}
        found = {
            name: media.resolve(
                file_name, "uploads", UPLOAD_KINDS[name], "an uploaded clip's", f"{where}.{name}"
            )
            for name, file_name in named.items()
        }
        missing = [name for name in exchange.UPLOAD_FILES if not found[name]]
        if missing:
            warnings.append(
                f"{where}: {missing[0]} file {named[missing[0]]!r} of "
                f"{condition.key} × {item.key} is not in media; left out."
            )
            continue
        save_checked(UploadedClip(condition=condition, item=item, **found, **values), where)
    return warnings
