"""Apply exclusion rules before analysis and report who was left out (spec 07)."""

import dataclasses
from collections.abc import Mapping, Sequence

import pandas as pd

from analysis.results import ExclusionReport
from analysis.tidy import TidyFormatError, split_flags


@dataclasses.dataclass(frozen=True)
class ExclusionRules:
    """Which participants to leave out: by flag, and by demographic answers."""

    pilot: bool = True
    failed_attention: bool = True
    incomplete: bool = True
    # Column → allowed values, e.g. {"asl_fluency": ("native", "expert")}.
    keep_only: Mapping[str, Sequence[str]] = dataclasses.field(default_factory=dict)


_FLAG_RULES = (
    ("pilot", "pilot"),
    ("failed_attention", "attention_failed"),
    ("incomplete", "incomplete"),
)


def apply_exclusions(
    frame: pd.DataFrame, rules: ExclusionRules = ExclusionRules()
) -> tuple[pd.DataFrame, ExclusionReport]:
    """Return the rows of included participants and a report of the exclusions.

    A participant is excluded when any of their rows carries an excluding flag, or
    their demographic answer is not among ``keep_only``'s values. The ``excluded``
    flag always excludes.
    """
    participant_flags = frame.groupby("participant")["flags"].agg(
        lambda cells: {flag for cell in cells for flag in split_flags(cell)}
    )
    reasons: dict[str, set] = {}
    for rule, flag in (*_FLAG_RULES, ("excluded", "excluded")):
        if rule == "excluded" or getattr(rules, rule):
            reasons[flag] = {who for who, flags in participant_flags.items() if flag in flags}
    for column, allowed in rules.keep_only.items():
        if column not in frame.columns:
            raise TidyFormatError(f"Cannot filter on {column!r}: the table has no such column.")
        values = frame.groupby("participant")[column].first()
        reasons[f"{column} not in {', '.join(map(str, allowed))}"] = set(
            values.index[~values.astype(str).isin([str(v) for v in allowed])]
        )
    excluded = set().union(*reasons.values()) if reasons else set()
    kept = frame[~frame["participant"].isin(excluded)]
    report = ExclusionReport(
        participants_total=int(frame["participant"].nunique()),
        participants_included=int(kept["participant"].nunique()),
        excluded_by_reason={reason: len(who) for reason, who in reasons.items() if who},
        rules={
            "pilot": rules.pilot,
            "failed_attention": rules.failed_attention,
            "incomplete": rules.incomplete,
            "keep_only": {k: list(v) for k, v in rules.keep_only.items()},
        },
    )
    return kept, report
