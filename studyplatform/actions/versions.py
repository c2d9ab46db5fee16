"""Make a new version of a study whose design is locked: a draft copy that counts on."""

from django.db import transaction

from studyplatform.actions.studies import duplicate_study, free_slug
from studyplatform.models import Study


def _base_slug(study: Study) -> str:
    first = study
    while first.previous_version is not None:
        first = first.previous_version
    return first.slug


def do_create_study_version(study: Study, *, owner) -> Study:
    """Return a new draft copy of *study* as its next version.

    The copy is numbered after *study* and any version already made from it, and its
    slug and title say so; *study* and its participants stay as they are, so every
    answer keeps the design it was given.
    """
    with transaction.atomic(durable=True):
        copy = duplicate_study(study, owner=owner)
        made = study.next_versions.exclude(pk=copy.pk).values_list("version", flat=True)
        number = max([study.version, *made]) + 1
        copy.version = number
        copy.previous_version = study
        copy.slug = free_slug(f"{_base_slug(study)}-v{number}")
        title = study.title.removesuffix(f" (version {study.version})")
        copy.title = f"{title} (version {number})"[:200]
        copy.save(update_fields=["version", "previous_version", "slug", "title"])
    return copy
