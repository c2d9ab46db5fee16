"""The planned design a power simulation repeats: who sees which trials (design.json).

A design is a list of schedules; participant j takes schedule j mod len(schedules), so
counterbalanced lists (Latin-square rows, swapped positions) are kept as they will run.
The JSON layout (docs/tidy-format.md, "Power planning")::

    {"kind": "pairwise" | "rating", "conditions": [...], "question": "clarity",
     "schedules": [[{"item": "GUITAR", "condition_a": "constant",
                     "condition_b": "variable"}, ...], ...]}
"""

import dataclasses
from pathlib import Path
from typing import Any

import pandas as pd

from analysis.results import Result
from analysis.tidy import TidyFormatError, analysed, read_json_file

KINDS = ("pairwise", "rating")


@dataclasses.dataclass(frozen=True)
class Trial(Result):
    """One planned trial: the item and the condition of clip 1 (and clip 2 for a pair)."""

    item: str
    condition_a: str
    condition_b: str = ""


@dataclasses.dataclass(frozen=True)
class PlannedDesign(Result):
    """What each participant will be shown; ``question`` names the rated question."""

    kind: str
    conditions: tuple[str, ...]
    schedules: tuple[tuple[Trial, ...], ...]
    question: str = ""

    def trials_per_participant(self) -> float:
        return sum(len(s) for s in self.schedules) / len(self.schedules)


def _schedule(schedule: Any, where: str, kind: str, conditions: tuple[str, ...]):
    """Check one participant's schedule (a list of trials) and return its trials."""
    if not isinstance(schedule, list) or not schedule:
        raise TidyFormatError(f"{where} must be a non-empty list.")
    trials = []
    for t, entry in enumerate(schedule):
        at = f"{where}, trial {t + 1}"
        if not isinstance(entry, dict):
            raise TidyFormatError(f"{at}: a trial is an object.")
        a, b = str(entry.get("condition_a", "")), str(entry.get("condition_b", ""))
        if a not in conditions or (kind == "pairwise" and b not in conditions):
            raise TidyFormatError(f"{at}: condition {a or b!r} is not in conditions.")
        if kind == "pairwise" and a == b:
            raise TidyFormatError(f"{at}: a pair needs two different conditions.")
        trials.append(Trial(str(entry.get("item", "")), a, b if kind == "pairwise" else ""))
    return tuple(trials)


def parse_design(data: Any, source: str = "design") -> PlannedDesign:
    """Check a design.json document and return it; errors name the problem."""
    if not isinstance(data, dict):
        raise TidyFormatError(f"{source}: a design is a JSON object.")
    kind = data.get("kind")
    if kind not in KINDS:
        raise TidyFormatError(f"{source}: kind must be one of {', '.join(KINDS)}, not {kind!r}.")
    conditions = data.get("conditions")
    if not isinstance(conditions, list) or len(conditions) < 2:
        raise TidyFormatError(f"{source}: conditions must list two or more condition names.")
    conditions = tuple(str(c) for c in conditions)
    schedules = data.get("schedules")
    if not isinstance(schedules, list) or not schedules:
        raise TidyFormatError(f"{source}: schedules must be a non-empty list of trial lists.")
    parsed = [
        _schedule(schedule, f"{source}: schedule {s + 1}", kind, conditions)
        for s, schedule in enumerate(schedules)
    ]
    return PlannedDesign(kind, conditions, tuple(parsed), str(data.get("question", "")))


def read_design(path: str | Path) -> PlannedDesign:
    """Read design.json (see the module docstring)."""
    return parse_design(read_json_file(path), str(path))


def design_from_responses(
    frame: pd.DataFrame, kind: str, question: str = "", conditions=None
) -> PlannedDesign:
    """Take each participant's trials in *frame* (a pilot) as one schedule of the design."""
    kinds = ("pairwise", "comparative") if kind == "pairwise" else ("rating",)
    rows = frame[frame["kind"].isin(kinds) & analysed(frame)]
    if kind == "rating":
        rows = rows[rows["question"].eq(question)]
    if rows.empty:
        raise TidyFormatError(
            f"no {kind} rows{f' for question {question!r}' if question else ''} to plan from."
        )
    if conditions is None:
        conditions = sorted((set(rows["condition_a"]) | set(rows["condition_b"])) - {""})
    schedules = tuple(
        tuple(
            Trial(item, a, b if kind == "pairwise" else "")
            for item, a, b in zip(
                group["item"], group["condition_a"], group["condition_b"], strict=True
            )
        )
        for _, group in rows.groupby("participant", sort=True)
    )
    return PlannedDesign(kind, tuple(conditions), schedules, question)
