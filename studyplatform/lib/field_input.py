"""Check values from outside (a study definition, a request) against the model fields they fill.

Django's ``full_clean`` trusts a value's Python type and skips a blank field's empty
values, so a definition's ``null`` for a text field, a list for a title, a NUL character
(which PostgreSQL cannot store) or an integer past the column's range reached the
database and failed there with a server error (issue 33). Every value of an import passes
here first; the message names what is wrong, to follow the field's name.
"""

import math
from typing import Any

from django.core.exceptions import FieldDoesNotExist
from django.db import models
from django.db.backends.base.operations import BaseDatabaseOperations


def _integer_range(field: models.Field) -> tuple[int, int]:
    # The standard column sizes (PostgreSQL's), on every database: SQLite would store any
    # 64-bit number in a small integer column, and a study moved to PostgreSQL then fails.
    ranges = BaseDatabaseOperations.integer_field_ranges
    return ranges.get(field.get_internal_type(), (-(2**63), 2**63 - 1))


def _text_problem(field: models.Field, value: Any) -> str | None:
    if not isinstance(value, str):
        return f"must be text, not {type(value).__name__}"
    return "must not contain a NUL character" if "\x00" in value else None


def _integer_problem(field: models.Field, value: Any) -> str | None:
    if isinstance(value, bool) or not isinstance(value, int):
        return f"must be a whole number, not {type(value).__name__}"
    low, high = _integer_range(field)
    return None if low <= value <= high else f"must be between {low} and {high}"


def _float_problem(field: models.Field, value: Any) -> str | None:
    if isinstance(value, bool) or not isinstance(value, int | float):
        return f"must be a number, not {type(value).__name__}"
    try:
        finite = math.isfinite(float(value))
    except OverflowError:  # an integer beyond any float
        finite = False
    return None if finite else "must be a finite number"


def _boolean_problem(field: models.Field, value: Any) -> str | None:
    return None if isinstance(value, bool) else "must be true or false"


def _object_problem(field: models.Field, value: Any) -> str | None:
    # Parameters, a design: objects, never lists.
    return None if isinstance(value, dict) else f"must be an object, not {type(value).__name__}"


# Each field class's check, the first that matches (AutoFields are IntegerFields).
_PROBLEMS = (
    (models.BooleanField, _boolean_problem),
    (models.CharField | models.TextField, _text_problem),
    (models.IntegerField, _integer_problem),
    (models.FloatField, _float_problem),
    (models.JSONField, _object_problem),
)


def value_problem(field: models.Field, value: Any) -> str | None:
    """Return why *value* cannot fill *field* (None if it can, for full_clean to judge)."""
    if value is None:
        return None if field.null else "must not be null"
    for kind, problem in _PROBLEMS:
        if isinstance(field, kind):
            return problem(field, value)
    return None


def values_problems(model: type[models.Model], values: dict[str, Any]) -> dict[str, str]:
    """Return, by field name, why each of *values* cannot fill *model*'s field."""
    problems = {}
    for name, value in values.items():
        try:
            field = model._meta.get_field(name)
        except FieldDoesNotExist:  # not a column (options, questions, …)
            continue
        if isinstance(field, models.ForeignKey):
            continue
        problem = value_problem(field, value)
        if problem:
            problems[name] = problem
    return problems
