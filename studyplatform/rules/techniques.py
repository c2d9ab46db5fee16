"""Check and describe a study's condition and item parameters with the technique registry.

A condition's parameters apply to every item of its study, so they are checked against
each item kind the study holds (against any kind while it holds none); an item's
against its own kind. The rules themselves live in :mod:`synthesis.techniques`. A pure
rule: the models' ``clean`` calls it, so it imports nothing of the platform (it reads a
saved condition's study through the instance it is given).
"""

from collections.abc import Iterable, Mapping
from typing import Any

from django.core.exceptions import ObjectDoesNotExist, ValidationError
from django.utils.translation import gettext

from studyplatform.rules.files import check_files
from synthesis.techniques import (
    FIELDS,
    REGISTRY,
    REQUEST_PARAMETERS,
    ClipError,
    as_checked,
    validate_parameters,
)

# A study's settings that are technique or filming values of its items: field → parameter.
STUDY_VALUES = {"manual_alphabet": "alphabet", "clip_width": "width", "clip_height": "height"}


def study_values(study, kind: str | None = None) -> dict[str, Any]:
    """Return the technique values *study* sets for its items (of *kind*: those its
    techniques take), its manual alphabet for words; an item's or a condition's own
    values override them."""
    if study is None:
        return {}
    values = {name: getattr(study, field) for field, name in STUDY_VALUES.items()}
    if kind is None:
        return values
    known = set(REGISTRY.parameters(kind)) | set(FIELDS) if kind in REGISTRY.kinds else set()
    return {name: value for name, value in values.items() if name in known}


def _technique_values(parameters: Mapping[str, Any]) -> dict[str, Any]:
    """Return *parameters* without the filming fields (view, size, seed …)."""
    return {k: v for k, v in parameters.items() if k not in FIELDS}


def supported_kinds(kinds: Iterable[str]) -> list[str]:
    """Return the item kinds among *kinds* that the engine renders, in a fixed order."""
    return sorted(kind for kind in set(kinds) if kind in REGISTRY.kinds)


def check_parameters(parameters: Any, kinds: Iterable[str], study=None) -> None:
    """Raise ClipError naming the problem if *parameters* do not suit every kind of *kinds*
    (with the values *study* sets for each kind, :func:`study_values`).

    With no kinds, they must suit at least one kind the engine renders.
    """
    kinds = supported_kinds(kinds)

    def with_study(kind: str) -> Any:
        if not isinstance(parameters, Mapping):
            return parameters
        return {**study_values(study, kind), **parameters}

    if kinds:
        for kind in kinds:
            validate_parameters(kind, with_study(kind))
        return
    errors = []
    for kind in REGISTRY.kinds:
        try:
            validate_parameters(kind, with_study(kind))
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
    """Raise ValidationError on the parameters field if they do not suit the study's items
    (their kinds, and each word's letters in the alphabet the condition spells it in)."""
    study = condition.study if condition.study_id is not None else None
    parameters = as_checked(condition.parameters or {})
    try:
        check_parameters(parameters, condition_item_kinds(condition), study)
    except ClipError as error:
        raise ValidationError({"parameters": str(error)}) from None
    check_files(condition.parameters, _study_owner(condition))
    if study is None or study.being_filled or not isinstance(condition.parameters, Mapping):
        return
    for item in study.items.all():
        try:
            check_text(item, as_checked({**item_values(study, item), **parameters}))
        except ClipError as error:
            raise ValidationError(
                {
                    "parameters": gettext("Item %(key)r: %(problem)s")
                    % {"key": item.key, "problem": error}
                }
            ) from None


def _study_owner(row):
    """Return the owner of *row*'s study (None for a row not in a study yet)."""
    return row.study.owner if row.study_id is not None else None


def check_item(item) -> None:
    """Raise ValidationError if the engine cannot render *item* under its study's conditions.

    Its text is checked as each rendered condition spells it (a word's letters in the
    alphabet the study, the item or the condition sets), and by a condition added later
    (:func:`check_condition`): a study without rendered conditions renders nothing, so
    its texts are the researcher's own words (a TİD study of uploaded clips spells ÇAY).
    """
    try:
        REGISTRY.kind(item.kind)
    except ClipError as error:
        raise ValidationError(
            {"kind": gettext("%(problem)s No technique renders it yet.") % {"problem": error}}
        ) from None
    try:
        validate_parameters(item.kind, item.parameters or {})
    except ClipError as error:
        raise ValidationError({"parameters": str(error)}) from None
    check_files(item.parameters, _study_owner(item))
    study = _study_of(item)
    own = item_values(study, item)
    if study is None:
        _item_text(item, as_checked(own), "")
    if study is None or study.pk is None:
        # A study added on one page with its items: its conditions are not saved yet.
        # The words are checked when it is saved again and when its clips are specified.
        return
    for condition in study.conditions.all():
        if condition.is_uploaded:
            continue
        parameters = as_checked({**own, **condition.parameters})
        try:
            validate_parameters(item.kind, parameters)
        except ClipError as error:
            raise ValidationError(
                {
                    "kind": gettext("Condition %(key)r cannot render this item: %(problem)s")
                    % {"key": condition.key, "problem": error}
                }
            ) from None
        _item_text(item, parameters, gettext("Condition %(key)r: ") % {"key": condition.key})


def check_study_values(study) -> None:
    """Raise ValidationError on a changed study setting (:data:`STUDY_VALUES`, its manual
    alphabet) that one of its rendered conditions cannot render an item with."""
    if study.pk is None or study.being_filled:
        return
    # Only the technique values decide whether a text can be signed: a new clip size
    # (a filming field) needs no pass over every item and condition.
    fields = [field for field, name in STUDY_VALUES.items() if name not in FIELDS]
    saved = type(study)._default_manager.filter(pk=study.pk).values(*fields).first()
    if saved is None or all(saved[field] == getattr(study, field) for field in fields):
        return
    rendered = [c for c in study.conditions.all() if not c.is_uploaded]
    for item in study.items.all() if rendered else ():
        own = item_values(study, item)
        for condition in rendered:
            try:
                check_text(item, as_checked({**own, **condition.parameters}))
            except ClipError as error:
                message = gettext("Item %(item)r under condition %(condition)r: %(problem)s") % {
                    "item": item.key,
                    "condition": condition.key,
                    "problem": error,
                }
                raise ValidationError(dict.fromkeys(fields, message)) from None


def item_values(study, item) -> dict[str, Any]:
    """Return the values *item* renders with before its condition's: its study's
    (:func:`study_values`), then its own parameters."""
    return {**study_values(study, item.kind), **(item.parameters or {})}


def check_text(item, parameters: Mapping[str, Any]) -> None:
    """Raise ClipError if *item*'s text cannot be signed with *parameters* (as a
    condition renders it, :func:`item_values` and the condition's; filming fields are
    left out): a word's letters in the alphabet they name."""
    REGISTRY.check_text(item.kind, item.text, _technique_values(parameters))


def _study_of(row):
    """Return *row*'s study: a saved one, one being added with it, or None."""
    try:
        return row.study
    except ObjectDoesNotExist:
        return None


def _item_text(item, parameters: Mapping[str, Any], where: str) -> None:
    """Raise ValidationError on the text field if *parameters* cannot sign it."""
    try:
        check_text(item, parameters)
    except ClipError as error:
        raise ValidationError({"text": f"{where}{error}"}) from None


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
