"""The platform's pure rules: checks the models' ``clean`` calls, importing no model.

Floors (docs/architecture.md): rules and questions ← models ← lib ← actions ← jobs,
views, admin; :mod:`tests.test_architecture` finds any import circle.
"""

from studyplatform.rules.files import FILE_SOURCES, check_files, file_help, resolve_files
from studyplatform.rules.techniques import (
    check_condition,
    check_item,
    check_parameters,
    check_study_values,
    condition_item_kinds,
    describe_condition,
    describe_parameters,
    item_values,
    study_values,
    supported_kinds,
)

__all__ = [
    "FILE_SOURCES",
    "check_condition",
    "check_files",
    "check_item",
    "check_parameters",
    "check_study_values",
    "condition_item_kinds",
    "describe_condition",
    "describe_parameters",
    "file_help",
    "item_values",
    "resolve_files",
    "study_values",
    "supported_kinds",
]
