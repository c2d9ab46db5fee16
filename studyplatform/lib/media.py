"""Read which media files the database still points at."""

from django.apps import apps
from django.db import models


def files_in_use(names) -> set[str]:
    """Return which of the media file *names* a row of any model's file field points at.

    A duplicated or imported study shares its files with the original, so a file is
    only garbage once no row of any study names it.
    """
    names = {name for name in names if name}
    used: set[str] = set()
    for model in apps.get_models():
        for field in model._meta.get_fields():
            if isinstance(field, models.FileField) and names - used:
                rows = model._default_manager.filter(**{f"{field.name}__in": names - used})
                used |= set(rows.values_list(field.name, flat=True))
    return used
