"""Check at start-up the invariants that tie the platform to the technique registry."""

from django.apps import apps
from django.core import checks

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
