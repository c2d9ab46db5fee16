"""Declare a technique's parameters as data, and check one value against its declaration.

A :class:`Parameter` is everything the platform needs to offer, check and record one
setting: its type, default, allowed values or range, units and help text. Validation,
command-line flags, admin form fields, the study JSON schema and the clip hash are all
derived from these declarations (docs/architecture.md, "The technique registry").
"""

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

TYPES = ("choice", "bool", "int", "float", "file")


class ClipError(ValueError):
    """A clip that cannot be specified or rendered as asked; the message names the field."""


@dataclass(frozen=True)
class Parameter:
    """One setting of a technique.

    *type* is one of :data:`TYPES`: ``choice`` (a string among *choices*), ``bool``,
    ``int`` and ``float`` (within *minimum*…*maximum*, in *units*), or ``file`` (a path;
    its content is part of the clip hash, "" means none). *labels* gives each choice a
    plain-words name for researchers.
    """

    name: str
    type: str
    default: Any
    help: str
    choices: tuple[str, ...] = ()
    labels: Mapping[str, str] | None = None
    minimum: float | None = None
    maximum: float | None = None
    units: str = ""

    def __post_init__(self) -> None:
        if self.type not in TYPES:
            raise ValueError(f"Parameter {self.name}: type must be one of {TYPES}.")
        if self.type == "choice" and self.default not in self.choices:
            raise ValueError(f"Parameter {self.name}: default {self.default!r} not a choice.")

    def check(self, value: Any) -> Any:
        """Return *value* as this parameter's type, or raise :class:`ClipError` naming it."""
        if self.type == "choice":
            if not isinstance(value, str) or value not in self.choices:
                raise ClipError(
                    f"Unknown {self.name} {value!r}; use one of {', '.join(self.choices)}."
                )
            return value
        if self.type == "bool":
            if not isinstance(value, bool):
                raise ClipError(f"{self.name} must be true or false, not {value!r}.")
            return value
        if self.type == "file":
            if not isinstance(value, str):
                raise ClipError(f"{self.name} must be a file path (text), not {value!r}.")
            return value
        return self._number(value)

    def _number(self, value: Any) -> int | float:
        # JSON true/false are ints to Python; a setting given as a boolean is a mistake.
        if isinstance(value, bool) or not isinstance(value, int | float):
            raise ClipError(f"{self.name} must be a number, not {value!r}.")
        if self.type == "int":
            if isinstance(value, float) and not value.is_integer():
                raise ClipError(f"{self.name} must be a whole number, not {value!r}.")
            value = int(value)
        else:
            if not math.isfinite(value):
                raise ClipError(f"{self.name} must be a finite number, not {value!r}.")
            value = float(value)
        if self.minimum is not None and value < self.minimum:
            raise ClipError(f"{self.name} must be at least {self.minimum:g}{self._unit()}.")
        if self.maximum is not None and value > self.maximum:
            raise ClipError(f"{self.name} must be at most {self.maximum:g}{self._unit()}.")
        return value

    def _unit(self) -> str:
        return f" {self.units}" if self.units else ""

    def label_of(self, value: Any) -> str:
        """Return *value* in plain words (a choice's label, a number with its units)."""
        if self.type == "choice" and self.labels:
            return self.labels.get(value, str(value))
        if self.type == "bool":
            return "on" if value else "off"
        if self.type == "file":
            return value or "none"
        if self.type in ("int", "float"):
            return f"{value:g}{self._unit()}"
        return str(value)

    def schema(self) -> dict:
        """Return this parameter as a JSON Schema property (the study file's schema)."""
        kind = {
            "choice": "string",
            "bool": "boolean",
            "int": "integer",
            "float": "number",
            "file": "string",
        }[self.type]
        schema: dict[str, Any] = {"type": kind, "default": self.default, "description": self.help}
        if self.choices:
            schema["enum"] = list(self.choices)
        if self.minimum is not None:
            schema["minimum"] = self.minimum
        if self.maximum is not None:
            schema["maximum"] = self.maximum
        if self.units:
            schema["x-units"] = self.units
        return schema
