"""Create studies from definitions: import, duplicate."""

from dataclasses import dataclass
from typing import Any

from django.db import transaction

from studyplatform.actions.import_media import ImportedMedia, StudyImportError
from studyplatform.actions.import_rows import import_rows, pick, save_checked
from studyplatform.actions.media import delete_unused_files_on_commit
from studyplatform.actions.recordings import relabel_stand_ins
from studyplatform.lib import exchange
from studyplatform.lib.bundle import BundleFiles, definition_files
from studyplatform.models import Study
from studyplatform.models.studies import LEGACY_CLIP_SIZE
from synthesis.formats import check_header


@dataclass(frozen=True)
class ImportResult:
    """The imported study and what was left out of it, with the reason."""

    study: Study
    warnings: tuple[str, ...] = ()


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
    labelled by the recordings that came (:func:`relabel_stand_ins`).

    One transaction: an import that fails, or a process killed half-way, leaves no
    study behind (issue 57); the files it had stored are removed when it fails.
    """
    media = ImportedMedia(owner, files, allowed_files)
    try:
        with transaction.atomic(durable=True):
            return import_study(
                data, owner=owner, slug=slug, title=title, status=status, media=media
            )
    except BaseException:
        _remove_stored(media.stored)
        raise


def import_study(
    data: Any,
    *,
    owner,
    media: ImportedMedia,
    slug: str | None = None,
    title: str | None = None,
    status: str | None = None,
) -> ImportResult:
    """Create the study of :func:`do_import_study` in the caller's transaction."""
    if not isinstance(data, dict):
        raise StudyImportError("A study definition must be a JSON object.")
    check_header(data, exchange.FORMAT, exchange.VERSION, "study definition", StudyImportError)
    values = pick(data.get("study"), exchange.STUDY_FIELDS, "study", Study)
    # A definition from before the clip size was a setting was made at the engine's size.
    values.setdefault("clip_width", LEGACY_CLIP_SIZE[0])
    values.setdefault("clip_height", LEGACY_CLIP_SIZE[1])
    if slug:
        values["slug"] = slug
    elif "slug" in values and isinstance(values["slug"], str):
        values["slug"] = free_slug(values["slug"])
    if title:
        values["title"] = title
    final_status = status or values.get("status") or Study.Status.DRAFT
    # A draft while its rows arrive: an open study's design is locked.
    study = Study(owner=owner, **{**values, "status": Study.Status.DRAFT})
    save_checked(study, "study")
    study.being_filled = True
    warnings = import_rows(data, study, media)
    study.being_filled = False
    study.status = final_status
    save_checked(study, "study")  # its status, checked like the rest
    relabel_stand_ins(study)
    return ImportResult(study=study, warnings=tuple(warnings))


def _remove_stored(stored: list) -> None:
    """Remove the files a failed import had stored (none of its rows survived)."""
    for storage, name in stored:
        delete_unused_files_on_commit(storage, [name])


def do_duplicate_study(study: Study, *, owner) -> Study:
    """Copy *study*'s definition into a new draft study owned by *owner*, in one transaction."""
    with transaction.atomic(durable=True):
        return duplicate_study(study, owner=owner)


def duplicate_study(study: Study, *, owner) -> Study:
    """Copy *study* as :func:`do_duplicate_study` does, in the caller's transaction.

    The copy keeps the signed templates attached to *study* and the conditions' avatars
    that *owner* may use (their own; any, for a superuser): a definition file leaves
    them out, since they belong to a researcher's library, not to the study.
    """
    definition = exchange.export_study(study)
    # The copy shares the original's files (deletion counts references).
    media = ImportedMedia(owner, None, definition_files(definition))
    result = import_study(
        definition,
        owner=owner,
        media=media,
        slug=free_slug(f"{study.slug}-copy"),
        title=f"{study.title} (copy)"[:200],
        status=Study.Status.DRAFT,
    )
    templates = study.signed_templates.all()
    if not owner.is_superuser:
        templates = templates.filter(owner=owner)
    result.study.signed_templates.set(templates)
    _keep_avatars(study, result.study, owner)
    return result.study


def _keep_avatars(study: Study, copy: Study, owner) -> None:
    """Film the copy's conditions with the original's avatars that *owner* may use."""
    for condition in study.conditions.exclude(avatar=None).select_related("avatar"):
        if owner.is_superuser or condition.avatar.owner_id == owner.pk:
            copy.conditions.filter(key=condition.key).update(avatar=condition.avatar)
