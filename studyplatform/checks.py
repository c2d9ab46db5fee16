"""Check at start-up the invariants that tie the platform to its registries: the
techniques' file parameters, the question types, and the study definition's fields."""

import re

from django.apps import apps
from django.core import checks
from django.template import TemplateDoesNotExist
from django.template.loader import get_template

from analysis.tidy import KINDS, SCALES
from studyplatform.rules.files import FILE_SOURCES, file_parameters


@checks.register()
def check_file_sources(app_configs=None, **kwargs) -> list[checks.CheckMessage]:
    """Every stored kind a file parameter takes must name a real parameter and model field."""
    errors = []
    declared = file_parameters()
    for name, sources in FILE_SOURCES.items():
        if name not in declared:
            errors.append(
                checks.Error(
                    f"FILE_SOURCES names {name!r}, which no technique declares as a file.",
                    hint="Name a parameter of type 'file' (python -m synthesis techniques).",
                    id="studyplatform.E001",
                )
            )
        for source in sources:
            model = apps.get_model("studyplatform", source.model)
            fields = {field.name for field in model._meta.get_fields()}
            if source.file_field not in fields:
                errors.append(
                    checks.Error(
                        f"{source.model} has no field {source.file_field!r} for {name!r}.",
                        id="studyplatform.E002",
                    )
                )
    return errors


@checks.register(deploy=True)
def check_confinement(app_configs=None, **kwargs) -> list[checks.CheckMessage]:
    """Warn where the kernel cannot keep confined parsers from the service's files."""
    from studyplatform.confine.jail import landlock_abi

    if landlock_abi() > 0:
        return []
    return [
        checks.Warning(
            "This kernel has no Landlock: confined parsers of uploaded files keep their "
            "memory, CPU, time and network limits but can read what the service can.",
            hint="Run on Linux 5.13 or newer with Landlock enabled (lsm=landlock,…).",
            id="studyplatform.W001",
        )
    ]


_KIND_NAME = re.compile(r"[a-z][a-z0-9_]*")


@checks.register()
def check_question_types(app_configs=None, **kwargs) -> list[checks.CheckMessage]:
    """Every registered question type must be storable, shown, exported and asked."""
    from studyplatform.models import Trial
    from studyplatform.questions import QUESTION_TYPES
    from studyplatform.questions.base import MAX_KIND_LENGTH

    problems = []
    for kind, type_ in QUESTION_TYPES.items():
        name = f"Question type {type(type_).__name__} ({kind!r})"
        if type_.kind != kind or not _KIND_NAME.fullmatch(kind) or len(kind) > MAX_KIND_LENGTH:
            problems.append(
                f"{name}: its kind must be the name it is registered by, lower-case letters, "
                f"digits and _, at most {MAX_KIND_LENGTH} characters."
            )
        if not type_.label:
            problems.append(f"{name} has no label (the admin names the kind by it).")
        try:
            get_template(type_.template)
        except TemplateDoesNotExist:
            problems.append(f"{name}: its template {type_.template!r} does not exist.")
        if type_.export_kind not in (None, *KINDS):
            problems.append(
                f"{name} exports as {type_.export_kind!r}, not a tidy-format kind "
                f"({', '.join(KINDS)}) or None."
            )
        if type_.export_kind == "rating" and type_.exported_scale not in SCALES:
            problems.append(
                f"{name} exports ratings on scale {type_.scale!r}, not one of {', '.join(SCALES)}."
            )
        unknown = sorted(set(type_.trial_kinds) - set(Trial.Kind.values))
        if not type_.trial_kinds or unknown:
            problems.append(
                f"{name} is asked on pages of kind {', '.join(unknown) or '(none)'}; "
                f"pages are {', '.join(Trial.Kind.values)}."
            )
    return [
        checks.Error(
            problem,
            hint="See docs/architecture.md, Recipe: add a question type.",
            id="studyplatform.E003",
        )
        for problem in problems
    ]


@checks.register()
def check_exchange_fields(app_configs=None, **kwargs) -> list[checks.CheckMessage]:
    """Every field of a definition's models must be exported or left out on purpose.

    Copies and versions go through export and import (do_duplicate_study), so a field
    on neither list would vanish from them silently (issue 39).
    """
    from studyplatform.lib.exchange import EXPORTED, LEFT_OUT

    problems = []
    if set(EXPORTED) != set(LEFT_OUT):
        problems.append(
            f"exchange.EXPORTED and LEFT_OUT name different models: "
            f"{sorted(set(EXPORTED) ^ set(LEFT_OUT))}."
        )
    for name, fields in EXPORTED.items():
        model = apps.get_model("studyplatform", name)
        present = {
            field.name
            for field in model._meta.get_fields()
            if (field.concrete or field.many_to_many) and not field.auto_created
        }
        left_out = set(LEFT_OUT.get(name, ()))
        for field in sorted(set(fields) & left_out):
            problems.append(f"{name}.{field} is both exported and left out.")
        for field in sorted(present - set(fields) - left_out):
            problems.append(f"{name}.{field} is neither exported nor left out on purpose.")
        for field in sorted((set(fields) | left_out) - present):
            problems.append(f"{name}.{field} is exported or left out but is no field.")
    return [
        checks.Error(
            problem,
            hint="Add it to exchange.py's field lists, or to LEFT_OUT saying why.",
            id="studyplatform.E004",
        )
        for problem in problems
    ]
