"""Turn a survey export with one row per participant into the tidy format, via a mapping.

The mapping (JSON, documented in docs/tidy-format.md) says which column holds the
participant id, which hold demographic answers, and what each answer column is: the
trial, item, conditions shown, question, and how its answer labels translate.
"""

import dataclasses
from pathlib import Path
from typing import Any

import pandas as pd

from analysis.tidy import (
    KINDS,
    NO_DIFFERENCE,
    REQUIRED_COLUMNS,
    TidyFormatError,
    check_responses,
    read_json_file,
)

MAPPING_FORMAT = "signstudy.wide-mapping"


@dataclasses.dataclass(frozen=True)
class ColumnMapping:
    """What one answer column of the survey export means."""

    column: str
    kind: str
    trial: str
    item: str = ""
    block: str = ""
    condition_a: str = ""
    condition_b: str = ""
    question: str = ""
    target: str = ""
    answers: dict[str, Any] = dataclasses.field(default_factory=dict)


@dataclasses.dataclass(frozen=True)
class WideMapping:
    """A whole survey export's mapping to the tidy format."""

    study: str
    participant: str
    columns: tuple[ColumnMapping, ...]
    attributes: dict[str, str] = dataclasses.field(default_factory=dict)
    header_rows: int = 1


def parse_mapping(data: Any, source: str = "mapping") -> WideMapping:
    """Check a mapping's JSON data and return it as a WideMapping."""
    if not isinstance(data, dict) or data.get("format") != MAPPING_FORMAT:
        raise TidyFormatError(
            f"{source}: not a column mapping ('format' must be {MAPPING_FORMAT!r})."
        )
    for key in ("study", "participant", "columns"):
        if key not in data:
            raise TidyFormatError(f"{source}: the mapping needs {key!r}.")
    fields = {f.name for f in dataclasses.fields(ColumnMapping)}
    columns = []
    for index, entry in enumerate(data["columns"]):
        where = f"{source}: columns[{index}]"
        if not isinstance(entry, dict):
            raise TidyFormatError(f"{where}: expected an object.")
        unknown = sorted(set(entry) - fields)
        if unknown:
            raise TidyFormatError(f"{where}: unknown key(s) {', '.join(unknown)}.")
        for key in ("column", "kind", "trial"):
            if not entry.get(key):
                raise TidyFormatError(f"{where}: needs {key!r}.")
        if entry["kind"] not in KINDS:
            raise TidyFormatError(
                f"{where}: kind {entry['kind']!r} is not one of {', '.join(KINDS)}."
            )
        columns.append(ColumnMapping(**entry))
    header_rows = data.get("header_rows", 1)
    if header_rows not in (1, 2):
        raise TidyFormatError(f"{source}: header_rows must be 1 or 2.")
    return WideMapping(
        study=str(data["study"]),
        participant=str(data["participant"]),
        columns=tuple(columns),
        attributes=dict(data.get("attributes", {})),
        header_rows=header_rows,
    )


def read_mapping(path: str | Path) -> WideMapping:
    """Read a mapping file (JSON)."""
    return parse_mapping(read_json_file(path), str(path))


def _column_names(wide: pd.DataFrame) -> list[str]:
    """Name each column; two header rows (SurveyMonkey) become "question | answer"."""
    if isinstance(wide.columns, pd.MultiIndex):
        names = []
        for top, sub in wide.columns:
            top = "" if str(top).startswith("Unnamed:") else str(top).strip()
            sub = "" if str(sub).startswith("Unnamed:") else str(sub).strip()
            names.append(f"{top} | {sub}" if top and sub else top or sub)
        return names
    return [str(name).strip() for name in wide.columns]


def _lookup(names: list[str], wanted: str, source: str) -> int:
    if wanted in names:
        return names.index(wanted)
    # With two header rows, a question's name alone finds it when it has one column.
    prefixed = [i for i, name in enumerate(names) if name.split(" | ")[0] == wanted]
    if len(prefixed) == 1:
        return prefixed[0]
    raise TidyFormatError(f"{source}: no column {wanted!r} in the survey export.")


def _answer(mapping: ColumnMapping, value: str, row: int, source: str) -> dict[str, Any]:
    where = f"{source}: row {row + 1}, column {mapping.column!r}"
    translated = mapping.answers.get(value, value)
    if mapping.kind == "pairwise":
        chosen = {"a": mapping.condition_a, "b": mapping.condition_b, "none": NO_DIFFERENCE}.get(
            str(translated)
        )
        if chosen is None:
            raise TidyFormatError(
                f"{where}: answer {value!r} is not in the mapping's answers "
                f"(map each label to 'a', 'b' or 'none')."
            )
        return {"chosen": chosen}
    if mapping.kind in ("rating", "comparative"):
        try:
            return {"rating": float(translated)}
        except (TypeError, ValueError):
            raise TidyFormatError(
                f"{where}: answer {value!r} is neither a number nor in the mapping's answers."
            ) from None
    return {"text": value}


def wide_to_tidy(wide: pd.DataFrame, mapping: WideMapping, source: str = "survey") -> pd.DataFrame:
    """Return the tidy table (checked) for a wide export; unanswered cells give no row."""
    names = _column_names(wide)
    participant_at = _lookup(names, mapping.participant, source)
    attribute_at = {
        name: _lookup(names, column, source) for name, column in mapping.attributes.items()
    }
    answer_at = [(m, _lookup(names, m.column, source)) for m in mapping.columns]
    rows = []
    values = wide.to_numpy(dtype=object)
    for index, record in enumerate(values):
        participant = str(record[participant_at]).strip()
        if not participant:
            raise TidyFormatError(f"{source}: row {index + 1} has no participant id.")
        attributes = {name: str(record[at]).strip() for name, at in attribute_at.items()}
        for column, at in answer_at:
            value = str(record[at]).strip()
            if not value:
                continue
            row = dict.fromkeys(REQUIRED_COLUMNS, "")
            row.update(
                participant=participant,
                study=mapping.study,
                block=column.block,
                trial=column.trial,
                item=column.item,
                kind=column.kind,
                condition_a=column.condition_a,
                condition_b=column.condition_b,
                question=column.question,
                target=column.target,
                **_answer(column, value, index, source),
                **attributes,
            )
            rows.append(row)
    if not rows:
        raise TidyFormatError(f"{source}: no answers found in the mapped columns.")
    tidy = pd.DataFrame(rows)
    if not tidy["target"].ne("").any():
        tidy = tidy.drop(columns=["target"])
    return check_responses(tidy.astype(str).replace("nan", ""), source)
