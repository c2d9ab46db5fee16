"""Create studies from definitions: import, duplicate."""

from dataclasses import dataclass
from pathlib import PurePosixPath
from typing import Any

from django.core.exceptions import ValidationError
from django.core.files.storage import default_storage
from django.db import models, transaction

from studyplatform import exchange
from studyplatform.actions.recordings import do_relabel_stand_ins
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
)


class StudyImportError(ValueError):
    """A study definition that cannot be imported; the message names the problem."""


@dataclass(frozen=True)
class ImportResult:
    """The imported study and what was left out of it, with the reason."""

    study: Study
    warnings: tuple[str, ...] = ()


def _pick(row: Any, fields: tuple[str, ...], where: str) -> dict[str, Any]:
    """Return *row*'s values for *fields*, rejecting anything else it holds."""
    if not isinstance(row, dict):
        raise StudyImportError(f"{where}: expected an object, got {type(row).__name__}.")
    unknown = sorted(set(row) - set(fields))
    if unknown:
        raise StudyImportError(f"{where}: unknown field(s) {', '.join(unknown)}.")
    return {name: row[name] for name in fields if name in row}


def _rows(data: dict[str, Any], name: str) -> list[Any]:
    rows = data.get(name, [])
    if not isinstance(rows, list):
        raise StudyImportError(f"{name}: expected a list.")
    return rows


def _save(obj: models.Model, where: str, exclude: list[str] | None = None) -> None:
    """Validate *obj* like a form would, then save it; name the failing field on error."""
    try:
        obj.full_clean(exclude=exclude)
    except ValidationError as error:
        details = "; ".join(
            f"{field}: {' '.join(messages)}" for field, messages in error.message_dict.items()
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
    data: dict[str, Any], name: str, model: type[models.Model], fields: tuple[str, ...], study
) -> dict[str, Any]:
    """Create the study's *name* rows of *model*; return them by key."""
    created = {}
    for index, row in enumerate(_rows(data, name)):
        where = f"{name}[{index}]"
        obj = model(study=study, **_pick(row, fields, where))
        _save(obj, where)
        created[obj.key] = obj
    return created


def free_slug(base: str) -> str:
    """Return *base*, or *base*-2, -3 … whichever no study uses yet."""
    base = base[:72]
    candidate, number = base, 1
    while Study.objects.filter(slug=candidate).exists():
        number += 1
        candidate = f"{base}-{number}"
    return candidate


def do_import_study(
    data: Any,
    *,
    owner,
    slug: str | None = None,
    title: str | None = None,
    status: str | None = None,
) -> ImportResult:
    """Create a study owned by *owner* from an exported definition, all or nothing.

    *slug*, *title* and *status* override the definition's. Without *slug*, the
    definition's slug is used, or a free variant of it when a study already has it.
    ASL videos and recordings whose files are not in this installation's media are left
    out, with a warning each; the motion-capture stand-ins are then labelled by the
    recordings that came (:func:`do_relabel_stand_ins`).
    """
    if not isinstance(data, dict):
        raise StudyImportError("A study definition must be a JSON object.")
    if data.get("format") != exchange.FORMAT:
        raise StudyImportError(
            f"Not a study definition: 'format' should be {exchange.FORMAT!r}, "
            f"got {data.get('format')!r}."
        )
    if data.get("version") != exchange.VERSION:
        raise StudyImportError(
            f"Unsupported study definition version {data.get('version')!r} "
            f"(this installation reads version {exchange.VERSION})."
        )
    warnings: list[str] = []
    with transaction.atomic():
        values = _pick(data.get("study"), exchange.STUDY_FIELDS, "study")
        if slug:
            values["slug"] = slug
        elif "slug" in values and isinstance(values["slug"], str):
            values["slug"] = free_slug(values["slug"])
        if title:
            values["title"] = title
        if status:
            values["status"] = status
        study = Study(owner=owner, **values)
        _save(study, "study")

        conditions = _create_keyed(data, "conditions", Condition, exchange.CONDITION_FIELDS, study)
        items = _create_keyed(data, "items", Item, exchange.ITEM_FIELDS, study)

        questions: dict[str, Question] = {}
        options: dict[str, AnswerOption] = {}
        for index, row in enumerate(_rows(data, "questions")):
            where = f"questions[{index}]"
            values = _pick(row, (*exchange.QUESTION_FIELDS, "options"), where)
            option_rows = values.pop("options", [])
            question = Question(study=study, **values)
            _save(question, where)
            questions[question.key] = question
            if not isinstance(option_rows, list):
                raise StudyImportError(f"{where}.options: expected a list.")
            for option_index, option_row in enumerate(option_rows):
                option_where = f"{where}.options[{option_index}]"
                option = AnswerOption(
                    question=question, **_pick(option_row, exchange.OPTION_FIELDS, option_where)
                )
                _save(option, option_where)
                options[f"{question.key}:{option.value}"] = option

        blocks = _create_keyed(data, "blocks", Block, exchange.BLOCK_FIELDS, study)

        trials: dict[str, Trial] = {}
        tables = {
            "block": blocks,
            "item": items,
            "condition_a": conditions,
            "condition_b": conditions,
        }
        for index, row in enumerate(_rows(data, "trials")):
            where = f"trials[{index}]"
            values = _pick(
                row, (*exchange.TRIAL_FIELDS, *exchange.TRIAL_REFERENCES, "questions"), where
            )
            question_keys = values.pop("questions", [])
            for ref in exchange.TRIAL_REFERENCES:
                kind = "condition" if ref.startswith("condition") else ref
                values[ref] = _lookup(tables[ref], values.get(ref), kind, f"{where}.{ref}")
            if values["block"] is None:
                raise StudyImportError(f"{where}.block: every trial belongs to a block.")
            trial = Trial(study=study, **values)
            _save(trial, where)
            if not isinstance(question_keys, list):
                raise StudyImportError(f"{where}.questions: expected a list of question keys.")
            asked = [
                _lookup(questions, key, "question", f"{where}.questions") for key in question_keys
            ]
            try:
                trial.check_questions(asked)
            except ValidationError as error:
                raise StudyImportError(f"{where}.questions: {' '.join(error.messages)}") from None
            trial.questions.set(asked)
            trials[trial.key] = trial

        targets = {
            "block": blocks,
            "trial": trials,
            "question": questions,
            "answeroption": options,
        }
        for index, row in enumerate(_rows(data, "asl_videos")):
            where = f"asl_videos[{index}]"
            values = _pick(row, (*exchange.ASL_VIDEO_FIELDS, "target", "video", "poster"), where)
            target_ref = values.pop("target", None)
            if not (isinstance(target_ref, list) and len(target_ref) == 2):
                raise StudyImportError(f"{where}.target: expected [model, key].")
            model, key = target_ref
            if model == "study":
                target = study
            elif isinstance(model, str) and model in targets:
                target = _lookup(targets[model], key, model, f"{where}.target")
            else:
                raise StudyImportError(f"{where}.target: unknown model {model!r}.")
            video_name = values.pop("video", "")
            _check_media_file(video_name, "asl", "an ASL video's", f"{where}.video")
            _check_media_file(values.get("poster"), "asl", "an ASL video's", f"{where}.poster")
            if not video_name or not default_storage.exists(video_name):
                warnings.append(f"{where}: video file {video_name!r} is not in media; left out.")
                continue
            video = AslVideo(target=target, video=video_name, **values)
            poster_name = values.get("poster") or ""
            if poster_name and not default_storage.exists(poster_name):
                video.poster = ""
                warnings.append(f"{where}: poster {poster_name!r} is not in media; left out.")
            _save(video, where)
        for index, row in enumerate(_rows(data, "recordings")):
            where = f"recordings[{index}]"
            values = _pick(row, ("item", *exchange.RECORDING_FIELDS, *exchange.RECORDING_FILES),
                           where)  # fmt: skip
            item = _lookup(items, values.pop("item", None), "item", f"{where}.item")
            if item is None or item.kind != Item.Kind.WORD:
                raise StudyImportError(f"{where}.item: recordings belong to words; "
                                       f"{getattr(item, 'key', None)!r} is not one.")  # fmt: skip
            files = {name: values.pop(name, "") or "" for name in exchange.RECORDING_FILES}
            for name, file_name in files.items():
                _check_media_file(file_name, "recordings", "a recording's", f"{where}.{name}")
            storage = Recording._meta.get_field("upload").storage  # private, not default
            missing = [name for name in ("upload", "motion")
                       if not files[name] or not storage.exists(files[name])]  # fmt: skip
            if missing:
                warnings.append(f"{where}: {missing[0]} file {files[missing[0]]!r} of {item.key} "
                                "is not in media; left out.")  # fmt: skip
                continue
            if files["sheet"] and not storage.exists(files["sheet"]):
                files["sheet"] = ""
            recording = Recording(item=item, status=Recording.Status.READY,
                                  progress_percent=100, **files, **values)  # fmt: skip
            _save(recording, where)
        do_relabel_stand_ins(study)
    return ImportResult(study=study, warnings=tuple(warnings))


def _check_media_file(name: Any, folder: str, whose: str, where: str) -> None:
    """Refuse a file name (empty: none) that is not one storage gives a file of *folder*
    (``folder/<name>``: no way out of media, nothing a definition could point elsewhere)."""
    if not name:
        return
    parts = PurePosixPath(name).parts if isinstance(name, str) else ()
    if not (len(parts) == 2 and parts[0] == folder and parts[1] not in ("", ".", "..")):
        raise StudyImportError(f"{where}: {name!r} is not {whose} file ({folder}/<name> in media).")


def do_duplicate_study(study: Study, *, owner) -> Study:
    """Copy *study*'s definition into a new draft study owned by *owner*."""
    result = do_import_study(
        exchange.export_study(study),
        owner=owner,
        slug=free_slug(f"{study.slug}-copy"),
        title=f"{study.title} (copy)"[:200],
        status=Study.Status.DRAFT,
    )
    return result.study
