"""Create studies from definitions: import, duplicate."""

from dataclasses import dataclass
from typing import Any

from django.core.exceptions import ValidationError
from django.db import models, transaction

from studyplatform import exchange
from studyplatform.actions.import_media import (
    ASL_POSTER,
    ASL_VIDEO,
    RECORDING_KINDS,
    ImportedMedia,
    StudyImportError,
)
from studyplatform.actions.media import delete_unused_files_on_commit
from studyplatform.actions.recordings import do_relabel_stand_ins
from studyplatform.lib.bundle import BundleFiles, definition_files
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
)
from synthesis.formats import check_header


@dataclass(frozen=True)
class ImportResult:
    """The imported study and what was left out of it, with the reason."""

    study: Study
    warnings: tuple[str, ...] = ()


def _pick(row: Any, fields: tuple[str, ...], where: str,
          model: type[models.Model] | None = None) -> dict[str, Any]:  # fmt: skip
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
    data: dict[str, Any], name: str, model: type[models.Model], fields: tuple[str, ...], study,
    save,
) -> dict[str, Any]:  # fmt: skip
    """Create the study's *name* rows of *model* with *save*; return them by key."""
    created = {}
    for index, row in enumerate(_rows(data, name)):
        where = f"{name}[{index}]"
        obj = model(study=study, **_pick(row, fields, where, model))
        save(obj, where)
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


# Rows saved per transaction while importing: SQLite has one writer, and a participant's
# save waits for the import's transaction to end (a 12,000-condition import in one
# transaction held it for 4.4 s).
BATCH_ROWS = 200


class _Batches:
    """Save rows in short transactions of at most *size* rows each."""

    def __init__(self, size: int = BATCH_ROWS):
        self.size, self.count, self._block = size, 0, None

    def save(self, obj: models.Model, where: str, exclude: list[str] | None = None) -> None:
        if self._block is None:
            self._block = transaction.atomic()
            self._block.__enter__()
        _save(obj, where, exclude)
        self.count += 1
        if self.count % self.size == 0:
            self.close()

    def close(self, *exc_info) -> None:
        """Commit the open transaction, or roll it back when given an exception's info."""
        block, self._block = self._block, None
        if block is not None:
            block.__exit__(*(exc_info or (None, None, None)))


def do_import_study(
    data: Any,
    *,
    owner,
    slug: str | None = None,
    title: str | None = None,
    status: str | None = None,
    files: BundleFiles | None = None,
    allowed_files: set[str] = frozenset(),
) -> ImportResult:
    """Create a study owned by *owner* from an exported definition, all or nothing.

    *slug*, *title* and *status* override the definition's. Without *slug*, the
    definition's slug is used, or a free variant of it when a study already has it.
    A media file the definition names must come in *files* (a bundle's, by media name;
    checked by content and stored under a name made from it) or be one *owner*'s studies
    already use (or one of *allowed_files*). Files in neither place, someone else's
    among them, are left out, with a warning each; the motion-capture stand-ins are then
    labelled by the recordings that came (:func:`do_relabel_stand_ins`).

    Rows are written in short transactions (BATCH_ROWS), so participants' saves never
    wait long; the study stays a draft until the import is complete, and an import that
    fails removes what it had written.
    """
    if not isinstance(data, dict):
        raise StudyImportError("A study definition must be a JSON object.")
    check_header(data, exchange.FORMAT, exchange.VERSION, "study definition", StudyImportError)
    values = _pick(data.get("study"), exchange.STUDY_FIELDS, "study", Study)
    if slug:
        values["slug"] = slug
    elif "slug" in values and isinstance(values["slug"], str):
        values["slug"] = free_slug(values["slug"])
    if title:
        values["title"] = title
    final_status = status or values.get("status") or Study.Status.DRAFT
    values["status"] = Study.Status.DRAFT
    study = Study(owner=owner, **values)
    with transaction.atomic():
        _save(study, "study")
    media = ImportedMedia(owner, files, allowed_files)
    batches = _Batches()
    try:
        # A draft while its rows arrive: an open study's design is locked.
        warnings = _import_rows(data, study, batches, media)
        batches.close()
        study.status = final_status
        with transaction.atomic():
            _save(study, "study")  # its status, checked like the rest
            do_relabel_stand_ins(study)
    except BaseException as error:
        batches.close(type(error), error, error.__traceback__)
        _discard(study, media.stored)
        raise
    return ImportResult(study=study, warnings=tuple(warnings))


def _discard(study: Study, stored: list) -> None:
    """Remove a failed import's rows and the files it had stored."""
    with transaction.atomic():
        for video in exchange.study_asl_videos(study):
            video.delete()
        Study.objects.filter(pk=study.pk).delete()
        for storage, name in stored:
            delete_unused_files_on_commit(storage, [name])


def _import_rows(data: dict, study: Study, batches: _Batches, media: ImportedMedia) -> list[str]:
    """Create every row of the definition *data* for *study*; return the warnings."""
    warnings: list[str] = []
    save = batches.save
    conditions = _create_keyed(data, "conditions", Condition, exchange.CONDITION_FIELDS, study,
                               save)  # fmt: skip
    items = _create_keyed(data, "items", Item, exchange.ITEM_FIELDS, study, save)

    questions: dict[str, Question] = {}
    options: dict[str, AnswerOption] = {}
    for index, row in enumerate(_rows(data, "questions")):
        where = f"questions[{index}]"
        values = _pick(row, (*exchange.QUESTION_FIELDS, "options"), where, Question)
        option_rows = values.pop("options", [])
        question = Question(study=study, **values)
        save(question, where)
        questions[question.key] = question
        if not isinstance(option_rows, list):
            raise StudyImportError(f"{where}.options: expected a list.")
        for option_index, option_row in enumerate(option_rows):
            option_where = f"{where}.options[{option_index}]"
            option = AnswerOption(
                question=question,
                **_pick(option_row, exchange.OPTION_FIELDS, option_where, AnswerOption),
            )
            save(option, option_where)
            options[f"{question.key}:{option.value}"] = option

    blocks = _create_keyed(data, "blocks", Block, exchange.BLOCK_FIELDS, study, save)

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
            row, (*exchange.TRIAL_FIELDS, *exchange.TRIAL_REFERENCES, "questions"), where, Trial
        )
        question_keys = values.pop("questions", [])
        for ref in exchange.TRIAL_REFERENCES:
            kind = "condition" if ref.startswith("condition") else ref
            values[ref] = _lookup(tables[ref], values.get(ref), kind, f"{where}.{ref}")
        if values["block"] is None:
            raise StudyImportError(f"{where}.block: every trial belongs to a block.")
        trial = Trial(study=study, **values)
        save(trial, where)
        if not isinstance(question_keys, list):
            raise StudyImportError(f"{where}.questions: expected a list of question keys.")
        asked = [_lookup(questions, key, "question", f"{where}.questions") for key in question_keys]
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
        values = _pick(row, (*exchange.ASL_VIDEO_FIELDS, "target", "video", "poster"), where,
                       AslVideo)  # fmt: skip
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
        video = media.resolve(video_name, "asl", ASL_VIDEO, "an ASL video's", f"{where}.video")
        poster = media.resolve(values.pop("poster", ""), "asl", ASL_POSTER, "an ASL video's",
                               f"{where}.poster")  # fmt: skip
        if not video:
            warnings.append(f"{where}: video file {video_name!r} is not in media; left out.")
            continue
        if poster is None:
            warnings.append(f"{where}: poster {row.get('poster')!r} is not in media; left out.")
        save(AslVideo(target=target, video=video, poster=poster or "", **values), where)
    for index, row in enumerate(_rows(data, "recordings")):
        where = f"recordings[{index}]"
        values = _pick(row, ("item", *exchange.RECORDING_FIELDS, *exchange.RECORDING_FILES),
                       where, Recording)  # fmt: skip
        item = _lookup(items, values.pop("item", None), "item", f"{where}.item")
        if item is None or item.kind != Item.Kind.WORD:
            raise StudyImportError(f"{where}.item: recordings belong to words; "
                                   f"{getattr(item, 'key', None)!r} is not one.")  # fmt: skip
        named = {name: values.pop(name, "") or "" for name in exchange.RECORDING_FILES}
        found = {name: media.resolve(file_name, "recordings", RECORDING_KINDS[name],
                                     "a recording's", f"{where}.{name}")
                 for name, file_name in named.items()}  # fmt: skip
        missing = [name for name in ("upload", "motion") if not found[name]]
        if missing:
            warnings.append(f"{where}: {missing[0]} file {named[missing[0]]!r} of {item.key} "
                            "is not in media; left out.")  # fmt: skip
            continue
        found["sheet"] = found["sheet"] or ""
        recording = Recording(item=item, status=Recording.Status.READY,
                              progress_percent=100, **found, **values)  # fmt: skip
        save(recording, where)
    return warnings


def do_duplicate_study(study: Study, *, owner) -> Study:
    """Copy *study*'s definition into a new draft study owned by *owner*.

    The copy keeps the signed templates attached to *study* that *owner* may attach
    (their own; any, for a superuser): a definition file leaves them out, since they
    belong to a researcher's library, not to the study.
    """
    definition = exchange.export_study(study)
    with transaction.atomic():
        result = do_import_study(
            definition,
            owner=owner,
            # The copy shares the original's files (deletion counts references).
            allowed_files=definition_files(definition),
            slug=free_slug(f"{study.slug}-copy"),
            title=f"{study.title} (copy)"[:200],
            status=Study.Status.DRAFT,
        )
        templates = study.signed_templates.all()
        if not owner.is_superuser:
            templates = templates.filter(owner=owner)
        result.study.signed_templates.set(templates)
    return result.study
