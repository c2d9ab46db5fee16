"""Check and describe a study's condition and item parameters with the technique registry.

A condition's parameters apply to every item of its study, so they are checked against
each item kind the study holds (against any kind while it holds none); an item's
against its own kind. The rules themselves live in :mod:`synthesis.techniques`. A pure
rule: the models' ``clean`` calls it, so it imports nothing of the platform (it reads a
saved condition's study through the instance it is given).
"""

from collections.abc import Iterable, Mapping
from typing import Any

from django.core.exceptions import ValidationError

from studyplatform.rules.files import check_files
from synthesis.techniques import (
    FIELDS,
    REGISTRY,
    REQUEST_PARAMETERS,
    ClipError,
    as_checked,
    validate_parameters,
)


def supported_kinds(kinds: Iterable[str]) -> list[str]:
    """Return the item kinds among *kinds* that the engine renders, in a fixed order."""
    return sorted(kind for kind in set(kinds) if kind in REGISTRY.kinds)


def check_parameters(parameters: Any, kinds: Iterable[str]) -> None:
    """Raise ClipError naming the problem if *parameters* do not suit every kind of *kinds*.

    With no kinds, they must suit at least one kind the engine renders.
    """
    kinds = supported_kinds(kinds)
    if kinds:
        for kind in kinds:
            validate_parameters(kind, parameters)
        return
    errors = []
    for kind in REGISTRY.kinds:
        try:
            validate_parameters(kind, parameters)
            return
        except ClipError as error:
            # The kind whose techniques know every key says what is wrong with a value.
            known = set(REGISTRY.parameters(kind)) | set(FIELDS)
            fits = isinstance(parameters, Mapping) and set(parameters) <= known
            if fits:
                errors.insert(0, error)
            else:
                errors.append(error)
    raise errors[0]


def condition_item_kinds(condition) -> list[str]:
    """Return the item kinds of the condition's study (none for a condition not in one)."""
    if condition is None or condition.study_id is None:
        return []
    if condition.study.being_filled:
        # An import creates a study's conditions before its items (check_item then
        # checks each item against them): there are none yet, and asking per condition
        # was a fifth of a large import's time in its one transaction.
        return []
    return list(condition.study.items.values_list("kind", flat=True))


def describe_condition(condition) -> str:
    """Return what a saved condition compares, in plain words ("—" for a new one)."""
    if condition is None or condition.pk is None:
        return "—"
    if getattr(condition, "is_uploaded", False):
        count = condition.uploads.count()
        return f"Uploaded clips ({count} uploaded; none rendered)"
    described = describe_parameters(
        as_checked(condition.parameters or {}), condition_item_kinds(condition)
    )
    if getattr(condition, "avatar_id", None) is not None:
        # The imported avatar films it: the built-in signer's description does not apply.
        described = [d for d in described if not d.startswith(("Avatar", "avatar"))]
        described.append(f"Avatar: your avatar “{condition.avatar}”")
    return "; ".join(described)


def check_condition(condition) -> None:
    """Raise ValidationError on the parameters field if they do not suit the study's items."""
    try:
        check_parameters(as_checked(condition.parameters or {}), condition_item_kinds(condition))
    except ClipError as error:
        raise ValidationError({"parameters": str(error)}) from None
    check_files(condition.parameters, _study_owner(condition))


def _study_owner(row):
    """Return the owner of *row*'s study (None for a row not in a study yet)."""
    return row.study.owner if row.study_id is not None else None


def check_item(item) -> None:
    """Raise ValidationError if the engine cannot render *item* under its study's conditions."""
    try:
        REGISTRY.kind(item.kind)
    except ClipError as error:
        raise ValidationError({"kind": f"{error} No technique renders it yet."}) from None
    try:
        REGISTRY.check_text(item.kind, item.text)
    except ClipError as error:
        raise ValidationError({"text": str(error)}) from None
    try:
        validate_parameters(item.kind, item.parameters or {})
    except ClipError as error:
        raise ValidationError({"parameters": str(error)}) from None
    check_files(item.parameters, _study_owner(item))
    if item.study_id is None:
        return
    for condition in item.study.conditions.all():
        try:
            parameters = as_checked({**(item.parameters or {}), **condition.parameters})
            validate_parameters(item.kind, parameters)
        except ClipError as error:
            raise ValidationError(
                {"kind": f"Condition {condition.key!r} cannot render this item: {error}"}
            ) from None


def _described(parameter, value) -> str:
    """Return a filming field's value in words; one that its check refuses as not valid
    (a form shown again with its errors describes what was posted)."""
    name = parameter.name.replace("_", " ")
    try:
        return f"{name} {parameter.label_of(parameter.check(value))}"
    except ClipError:
        return f"{name}: not valid"


def describe_parameters(parameters: Mapping[str, Any], kinds: Iterable[str]) -> list[str]:
    """Return what *parameters* make each technique do, in plain words.

    One line per technique of each of *kinds* (of each kind they suit, with no kinds),
    then one for the filming fields they set.
    """
    chosen = supported_kinds(kinds)
    techniques = {k: v for k, v in parameters.items() if k not in FIELDS}
    lines = []
    for kind in chosen or list(REGISTRY.kinds):
        try:
            validate_parameters(kind, parameters)
        except ClipError as error:
            if chosen:
                lines.append(f"Not renderable as a {REGISTRY.kind(kind).label}: {error}")
            continue
        lines += [line for line in REGISTRY.describe(kind, techniques) if line not in lines]
    filming = [
        _described(p, parameters[p.name]) for p in REQUEST_PARAMETERS if p.name in parameters
    ]
    if filming:
        lines.append(f"Filming: {', '.join(filming)}")
    return lines
