"""Apply exclusion rules before analysis and report who was left out (spec 07)."""

import dataclasses
from collections.abc import Mapping, Sequence

import pandas as pd

from analysis.results import ExclusionReport
from analysis.tidy import TidyFormatError, analysed, split_flags


@dataclasses.dataclass(frozen=True)
class ExclusionRules:
    """Which participants to leave out: by flag, and by demographic answers."""

    pilot: bool = True
    failed_attention: bool = True
    incomplete: bool = True
    # Column → allowed values, e.g. {"asl_fluency": ("native", "expert")}.
    keep_only: Mapping[str, Sequence[str]] = dataclasses.field(default_factory=dict)
    # Speeders: an answer given before the page's clips had played to their end.
    answered_before_end: bool = False
    # Participants whose median time on a page is below this many seconds.
    min_median_page_s: float | None = None

    def to_dict(self) -> dict:
        """Return the rules as JSON-ready data."""
        return {
            "pilot": self.pilot,
            "failed_attention": self.failed_attention,
            "incomplete": self.incomplete,
            "keep_only": {k: list(v) for k, v in self.keep_only.items()},
            "answered_before_end": self.answered_before_end,
            "min_median_page_s": self.min_median_page_s,
        }


ANSWERED_EARLY = "answered before the clips ended"

_FLAG_RULES = (
    ("pilot", "pilot"),
    ("failed_attention", "attention_failed"),
    ("incomplete", "incomplete"),
)


def _flag_reasons(frame: pd.DataFrame, rules: ExclusionRules) -> dict[str, set]:
    """Return the participants each flag rule excludes (and ``excluded``, always)."""
    participant_flags = frame.groupby("participant")["flags"].agg(
        lambda cells: {flag for cell in cells for flag in split_flags(cell)}
    )
    reasons: dict[str, set] = {}
    for rule, flag in (*_FLAG_RULES, ("excluded", "excluded")):
        if rule == "excluded" or getattr(rules, rule):
            reasons[flag] = {who for who, flags in participant_flags.items() if flag in flags}
    return reasons


def _answer_reasons(frame: pd.DataFrame, rules: ExclusionRules) -> dict[str, set]:
    """Return the participants whose demographic answer is not among ``keep_only``'s."""
    reasons: dict[str, set] = {}
    for column, allowed in rules.keep_only.items():
        if column not in frame.columns:
            raise TidyFormatError(f"Cannot filter on {column!r}: the table has no such column.")
        values = frame.groupby("participant")[column].first()
        reasons[f"{column} not in {', '.join(map(str, allowed))}"] = set(
            values.index[~values.astype(str).isin([str(v) for v in allowed])]
        )
    return reasons


def apply_exclusions(
    frame: pd.DataFrame, rules: ExclusionRules = ExclusionRules()
) -> tuple[pd.DataFrame, ExclusionReport]:
    """Return the rows of included participants and a report of the exclusions.

    A participant is excluded when any of their rows carries an excluding flag, or
    their demographic answer is not among ``keep_only``'s values. The ``excluded``
    flag always excludes.
    """
    reasons = {**_flag_reasons(frame, rules), **_answer_reasons(frame, rules)}
    reasons.update(_behaviour_reasons(frame, rules))
    excluded = set().union(*reasons.values()) if reasons else set()
    kept = frame[~frame["participant"].isin(excluded)]
    by_participant: dict[str, list[str]] = {}
    for reason, who in reasons.items():
        for participant in who:
            by_participant.setdefault(str(participant), []).append(reason)
    report = ExclusionReport(
        participants_total=int(frame["participant"].nunique()),
        participants_included=int(kept["participant"].nunique()),
        excluded_by_reason={reason: len(who) for reason, who in reasons.items() if who},
        rules=rules.to_dict(),
        excluded_participants={p: sorted(r) for p, r in sorted(by_participant.items())},
    )
    return kept, report


def _needs(frame: pd.DataFrame, column: str, rule: str) -> pd.Series:
    if column not in frame.columns:
        raise TidyFormatError(
            f"The rule “{rule}” needs the column {column!r}, which the table lacks "
            "(SignStudy's export has it; see docs/tidy-format.md)."
        )
    return pd.to_numeric(frame[column], errors="coerce")


def _behaviour_reasons(frame: pd.DataFrame, rules: ExclusionRules) -> dict[str, set]:
    """Return the participants each behavioural rule excludes (speeders, fast pages)."""
    reasons: dict[str, set] = {}
    rows = frame[analysed(frame)]
    if rules.answered_before_end:
        early = _needs(rows, "answered_before_end", ANSWERED_EARLY).eq(1)
        reasons[ANSWERED_EARLY] = set(rows.loc[early, "participant"])
    if rules.min_median_page_s is not None:
        reason = f"median time on a page under {rules.min_median_page_s:g} s"
        pages = rows.assign(_ms=_needs(rows, "time_on_page_ms", reason))
        # One value per page: a page with several questions repeats its time on each row.
        per_page = pages.dropna(subset=["_ms"]).groupby(["participant", "trial"])["_ms"].first()
        medians = per_page.groupby(level="participant").median()
        reasons[reason] = set(medians.index[medians < 1000 * rules.min_median_page_s])
    return reasons
