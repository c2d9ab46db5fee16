"""Read and check the tidy response table: one row per participant × trial (× question).

The format is documented in docs/tidy-format.md. Every problem is reported as one
:class:`TidyFormatError` whose message names the file, row and column.
"""

import json
from collections.abc import Iterable
from pathlib import Path
from typing import IO

import numpy as np
import pandas as pd

REQUIRED_COLUMNS = (
    "participant",
    "study",
    "block",
    "trial",
    "item",
    "kind",
    "condition_a",
    "condition_b",
    "chosen",
    "question",
    "rating",
    "text",
    "rt_ms",
    "flags",
)
# Optional columns with a meaning of their own; any other column is a participant
# attribute (a demographic answer) and must be constant within a participant.
# How each page was taken (SignStudy's export; docs/tidy-format.md "Quality columns").
QUALITY_COLUMNS = (
    "page_order",
    "shown_at",
    "answered_at",
    "time_on_page_ms",
    "clip1_plays",
    "clip2_plays",
    "clip1_ended",
    "clip2_ended",
    "replays",
    "playback_errors",
    "answered_before_end",
    "viewport",
    "device",
)
# A signed (webcam) answer's file: its SHA-256 (the name it has in the "everything" zip,
# signed_answers/<sha256>.<ext>) and where its researchers download it.
SIGNED_COLUMNS = ("video_sha256", "video_url")
# The name a researcher gave each clip's condition (SignStudy's condition label); the
# analysis names conditions by them, and keeps the keys in *_key columns.
LABEL_COLUMNS = {"condition_a": "condition_a_label", "condition_b": "condition_b_label"}
KEY_COLUMNS = {"condition_a": "condition_a_key", "condition_b": "condition_b_key"}
# Where each clip as shown came from ("rendered" by the engine or "uploaded" by the
# researcher) and the SHA-256 of the file participants were sent.
SOURCE_COLUMNS = ("condition_a_source", "condition_b_source", "clip1_sha256", "clip2_sha256")
UPLOADED = "uploaded"
# What a rating question's values are (the ``scale`` column; empty reads as ordinal):
# ordinal points get cumulative-link and linear mixed models, a continuous scale (a
# slider) the linear model only.
SCALES = ("ordinal", "continuous")
ORDINAL, CONTINUOUS = SCALES
OPTIONAL_COLUMNS = (
    "target",
    "scale",
    "condition_simulated",
    *SOURCE_COLUMNS,
    *LABEL_COLUMNS.values(),
    *KEY_COLUMNS.values(),
    *QUALITY_COLUMNS,
    *SIGNED_COLUMNS,
)
# How a simulated condition is named in every result: a reader must never take a
# simulated stand-in (e.g. for motion capture) for the real thing.
SIMULATED_SUFFIX = " (simulated)"
KINDS = ("pairwise", "comparative", "rating", "text")
NO_DIFFERENCE = "none"
# Flags that exclude a participant, and flags that take a row out of the analyses.
PARTICIPANT_FLAGS = ("pilot", "attention_failed", "incomplete", "excluded")
ROW_FLAGS = ("practice", "attention_check")
KNOWN_FLAGS = PARTICIPANT_FLAGS + ROW_FLAGS


class TidyFormatError(ValueError):
    """A response table that does not follow the tidy format; the message says where."""


def read_json_file(path: str | Path):
    """Read a JSON settings file (mapping, design, effects); errors name the file."""
    try:
        return json.loads(Path(path).read_text(encoding="utf-8"))
    except FileNotFoundError:
        raise TidyFormatError(f"{path}: no such file.") from None
    except json.JSONDecodeError as error:
        raise TidyFormatError(
            f"{path}: not valid JSON ({error.msg}, line {error.lineno})."
        ) from None


def _row_label(index: int) -> str:
    # Data row 1 is line 2 of the file, after the header.
    return f"row {index + 1} (line {index + 2})"


def _numeric(frame: pd.DataFrame, column: str, source: str) -> pd.Series:
    raw = frame[column]
    values = pd.to_numeric(raw, errors="coerce")
    bad = values.isna() & raw.ne("")
    if bad.any():
        index = int(np.flatnonzero(bad.to_numpy())[0])
        raise TidyFormatError(
            f"{source}: {_row_label(index)}: {column} {raw.iloc[index]!r} is not a number."
        )
    return values


def check_responses(frame: pd.DataFrame, source: str = "responses") -> pd.DataFrame:
    """Validate a raw table and return it typed: strings stripped, numbers as floats.

    Raise TidyFormatError naming the first problem found.
    """
    missing = [column for column in REQUIRED_COLUMNS if column not in frame.columns]
    if missing:
        raise TidyFormatError(
            f"{source}: missing column(s) {', '.join(missing)}; the tidy format needs "
            f"{', '.join(REQUIRED_COLUMNS)} (see docs/tidy-format.md)."
        )
    if frame.empty:
        raise TidyFormatError(f"{source}: no response rows.")
    frame = frame.copy()
    for column in frame.columns:
        # A numeric column (a frame built in memory) becomes text like one read from CSV.
        values = frame[column].astype(object)
        frame[column] = values.where(values.notna(), "").astype(str).str.strip()
    frame["rating"] = _numeric(frame, "rating", source)
    frame["rt_ms"] = _numeric(frame, "rt_ms", source)

    for column in ("participant", "kind"):
        empty = frame[column].eq("")
        if empty.any():
            index = int(np.flatnonzero(empty.to_numpy())[0])
            raise TidyFormatError(f"{source}: {_row_label(index)}: {column} is empty.")
    unknown_kind = ~frame["kind"].isin(KINDS)
    if unknown_kind.any():
        index = int(np.flatnonzero(unknown_kind.to_numpy())[0])
        raise TidyFormatError(
            f"{source}: {_row_label(index)}: kind {frame['kind'].iloc[index]!r} is not one of "
            f"{', '.join(KINDS)}."
        )
    _check_flags(frame, source)
    _check_pairwise(frame, source)
    _check_ratings(frame, source)
    return label_simulated(label_conditions(frame))


def simulated_conditions(frame: pd.DataFrame) -> list[str]:
    """Return the conditions the ``condition_simulated`` column names, sorted."""
    if "condition_simulated" not in frame.columns:
        return []
    return sorted({c for cell in frame["condition_simulated"] for c in split_flags(cell)})


def uploaded_conditions(frame: pd.DataFrame) -> list[str]:
    """Return the conditions whose clips the source columns say were uploaded, sorted."""
    found = set()
    for column in ("condition_a", "condition_b"):
        source = f"{column}_source"
        if source in frame.columns:
            found.update(frame.loc[frame[source].eq(UPLOADED), column])
    return sorted(found - {""})


def condition_labels(frame: pd.DataFrame) -> dict[str, str]:
    """Return condition key → label from the label columns, where the label can name it.

    A key keeps its name where it has no label, or where its label is another
    condition's label or key (names must stay one-to-one), or ``none``.
    """
    found: dict[str, str] = {}
    for column, label_column in LABEL_COLUMNS.items():
        if label_column in frame.columns:
            for key, label in zip(frame[column], frame[label_column], strict=True):
                if key and label:
                    found.setdefault(key, label)
    keys = set(frame["condition_a"]) | set(frame["condition_b"])
    names = [found.get(key, key) for key in keys]
    return {
        key: label
        for key, label in found.items()
        if label != key and label != NO_DIFFERENCE and label not in keys and names.count(label) == 1
    }


def _rename(frame: pd.DataFrame, rename: dict[str, str]) -> pd.DataFrame:
    """Return *frame* with conditions renamed in the clip, choice and simulated columns."""
    frame = frame.copy()
    for column in ("condition_a", "condition_b", "chosen"):
        frame[column] = frame[column].replace(rename)
    if "condition_simulated" in frame.columns:
        frame["condition_simulated"] = frame["condition_simulated"].map(
            lambda cell: ";".join(rename.get(c, c) for c in split_flags(cell))
        )
    return frame


def label_conditions(frame: pd.DataFrame) -> pd.DataFrame:
    """Return *frame* with each condition named by its label (condition_labels), the keys
    kept in ``condition_a_key`` / ``condition_b_key`` and the label columns dropped.

    The help text of a SignStudy condition's label promises it is the name reports use.
    """
    present = [column for column in LABEL_COLUMNS.values() if column in frame.columns]
    if not present:
        return frame
    labels = condition_labels(frame)
    keys = {KEY_COLUMNS[column]: frame[column] for column in LABEL_COLUMNS}
    return _rename(frame, labels).drop(columns=present).assign(**keys)


def condition_keys(frame: pd.DataFrame) -> dict[str, str]:
    """Return each condition's name in *frame* → its key, where the two differ."""
    found: dict[str, str] = {}
    for column, key_column in KEY_COLUMNS.items():
        if key_column in frame.columns:
            for name, key in zip(frame[column], frame[key_column], strict=True):
                if name and key and name.removesuffix(SIMULATED_SUFFIX) != key:
                    found.setdefault(name, key)
    return dict(sorted(found.items()))


def label_simulated(frame: pd.DataFrame) -> pd.DataFrame:
    """Return *frame* with each simulated condition renamed ``"<key> (simulated)"``.

    The rename covers both clip columns and pairwise choices, so every table, figure
    and report made from the frame names the condition simulated.
    """
    simulated = [c for c in simulated_conditions(frame) if not c.endswith(SIMULATED_SUFFIX)]
    if not simulated:
        return frame
    return _rename(frame, {key: key + SIMULATED_SUFFIX for key in simulated})


def with_simulated_labels(conditions: Iterable[str], frame: pd.DataFrame) -> tuple[str, ...]:
    """Return *conditions* (keys or labels) named as the frame names them: by label where
    the condition has one, simulated ones marked so."""
    names = {key: name for name, key in condition_keys(frame).items()}
    labelled = set(simulated_conditions(frame))
    named = [names.get(c, c) for c in conditions]
    return tuple(c + SIMULATED_SUFFIX if c + SIMULATED_SUFFIX in labelled else c for c in named)


def _check_flags(frame: pd.DataFrame, source: str) -> None:
    for index, flags in enumerate(frame["flags"]):
        for flag in split_flags(flags):
            if flag not in KNOWN_FLAGS:
                raise TidyFormatError(
                    f"{source}: {_row_label(index)}: unknown flag {flag!r} "
                    f"(known: {', '.join(KNOWN_FLAGS)})."
                )


def _check_pairwise(frame: pd.DataFrame, source: str) -> None:
    pairs = frame["kind"].isin(("pairwise", "comparative"))
    for column in ("condition_a", "condition_b"):
        empty = pairs & frame[column].eq("")
        if empty.any():
            index = int(np.flatnonzero(empty.to_numpy())[0])
            raise TidyFormatError(
                f"{source}: {_row_label(index)}: a {frame['kind'].iloc[index]} row needs {column}."
            )
    choice = frame["kind"].eq("pairwise")
    valid = (
        frame["chosen"].eq(frame["condition_a"])
        | frame["chosen"].eq(frame["condition_b"])
        | frame["chosen"].eq(NO_DIFFERENCE)
    )
    bad = choice & ~valid
    if bad.any():
        index = int(np.flatnonzero(bad.to_numpy())[0])
        row = frame.iloc[index]
        raise TidyFormatError(
            f"{source}: {_row_label(index)}: chosen {row['chosen']!r} is neither condition_a "
            f"{row['condition_a']!r}, condition_b {row['condition_b']!r} nor 'none'."
        )
    unrated = frame["kind"].eq("comparative") & frame["rating"].isna()
    if unrated.any():
        index = int(np.flatnonzero(unrated.to_numpy())[0])
        raise TidyFormatError(f"{source}: {_row_label(index)}: a comparative row needs a rating.")


def _check_ratings(frame: pd.DataFrame, source: str) -> None:
    ratings = frame["kind"].eq("rating")
    for column in ("condition_a", "question"):
        empty = ratings & frame[column].eq("")
        if empty.any():
            index = int(np.flatnonzero(empty.to_numpy())[0])
            raise TidyFormatError(f"{source}: {_row_label(index)}: a rating row needs {column}.")
    unrated = ratings & frame["rating"].isna()
    if unrated.any():
        index = int(np.flatnonzero(unrated.to_numpy())[0])
        raise TidyFormatError(f"{source}: {_row_label(index)}: a rating row needs a rating.")
    if "scale" in frame.columns:
        _check_scales(frame, ratings, source)


def _check_scales(frame: pd.DataFrame, ratings: pd.Series, source: str) -> None:
    unknown = ratings & ~frame["scale"].isin(("", *SCALES))
    if unknown.any():
        index = int(np.flatnonzero(unknown.to_numpy())[0])
        raise TidyFormatError(
            f"{source}: {_row_label(index)}: scale {frame['scale'].iloc[index]!r} is not one "
            f"of {', '.join(SCALES)} (or empty: ordinal)."
        )
    rated = frame[ratings]
    scales = rated["scale"].replace("", ORDINAL).groupby(rated["question"]).nunique()
    mixed = sorted(scales.index[scales > 1])
    if mixed:
        raise TidyFormatError(
            f"{source}: question {mixed[0]!r} has rating rows on more than one scale."
        )


def rating_scale(frame: pd.DataFrame, question: str) -> str:
    """Return the scale of *question*'s ratings: ``continuous`` if its rows say so, else
    ``ordinal`` (tables without the column, and points, are ordinal)."""
    if "scale" not in frame.columns:
        return ORDINAL
    asked = frame.loc[frame["kind"].eq("rating") & frame["question"].eq(question), "scale"]
    return CONTINUOUS if asked.eq(CONTINUOUS).any() else ORDINAL


def split_flags(flags: str) -> list[str]:
    """Return the flags of a ``flags`` cell ("pilot;practice" → ["pilot", "practice"])."""
    return [flag.strip() for flag in flags.replace(",", ";").split(";") if flag.strip()]


def analysed(frame: pd.DataFrame) -> pd.Series:
    """Return a mask of the rows analyses use: not practice, not attention checks."""
    # astype: mapping no rows gives a str column, which pandas 4 will not combine with &.
    flagged = frame["flags"].map(lambda cell: any(f in ROW_FLAGS for f in split_flags(cell)))
    return ~flagged.astype(bool)


def read_responses(path_or_file: str | Path | IO[str]) -> pd.DataFrame:
    """Read a tidy CSV and return the checked table (see :func:`check_responses`)."""
    source = str(getattr(path_or_file, "name", path_or_file))
    try:
        frame = pd.read_csv(path_or_file, dtype=str, keep_default_na=False)
    except FileNotFoundError:
        raise TidyFormatError(f"{source}: no such file.") from None
    except pd.errors.EmptyDataError:
        raise TidyFormatError(f"{source}: the file is empty.") from None
    except (pd.errors.ParserError, UnicodeDecodeError) as error:
        first_line = str(error).strip().splitlines()[0]
        raise TidyFormatError(f"{source}: not a readable CSV file ({first_line}).") from None
    return check_responses(unescape_cells(frame), source)


def unescape_cells(frame: pd.DataFrame) -> pd.DataFrame:
    """Return a table read from CSV with the spreadsheet escape taken off: one leading
    apostrophe, which SignStudy's export puts before a cell a spreadsheet would run as
    a formula, and before a cell that starts with an apostrophe (docs/tidy-format.md)."""
    return frame.apply(lambda column: column.where(~column.str.startswith("'"), column.str[1:]))


def participant_attributes(frame: pd.DataFrame) -> list[str]:
    """Return the demographic columns: every column the format does not define."""
    return [
        column
        for column in frame.columns
        if column not in REQUIRED_COLUMNS and column not in OPTIONAL_COLUMNS
    ]


def check_conditions(frame: pd.DataFrame, conditions: Iterable[str], source: str) -> None:
    """Raise TidyFormatError if a listed condition is never shown or an unlisted one is."""
    conditions = list(conditions)
    pairs = frame[frame["kind"].isin(("pairwise", "comparative", "rating"))]
    shown = (set(pairs["condition_a"]) | set(pairs["condition_b"])) - {""}
    unknown = sorted(shown - set(conditions))
    if unknown:
        raise TidyFormatError(
            f"{source}: unknown condition(s) {', '.join(unknown)}; expected "
            f"{', '.join(conditions)}."
        )
    never = [condition for condition in conditions if condition not in shown]
    if never:
        raise TidyFormatError(f"{source}: condition(s) {', '.join(never)} never shown.")
