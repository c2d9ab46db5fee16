"""List a study's participants for the researcher: status, review, exclusions, device."""

from dataclasses import dataclass
from datetime import timedelta

from django.utils.translation import gettext

from analysis import ExclusionRules, TidyFormatError, apply_exclusions
from studyplatform.lib.export import tidy_table
from studyplatform.lib.quality import device_of
from studyplatform.models import Participant, Study


@dataclass(frozen=True)
class RosterRow:
    """One participant as the participants page shows them."""

    participant: Participant
    status: str
    duration: timedelta | None
    device: str
    pages: str
    recruitment_id: str
    reasons: tuple[str, ...]


def exclusion_reasons(study: Study, rules: ExclusionRules) -> tuple[dict[str, list[str]], str]:
    """Return participant id → the reasons *rules* exclude them for, and any data problem."""
    try:
        table = tidy_table(study)
        if table is None:
            return {}, ""
        _, report = apply_exclusions(table, rules)
    except TidyFormatError as problem:
        return {}, str(problem)
    return report.excluded_participants, ""


def _status(participant: Participant) -> str:
    if participant.is_pilot:
        return "pilot"
    return "complete" if participant.is_finished else "incomplete"


def roster(study: Study, rules: ExclusionRules) -> tuple[list[RosterRow], str]:
    """Return the study's participants, newest first, and any problem reading the data."""
    reasons, problem = exclusion_reasons(study, rules)
    rows = []
    for participant in study.participants.order_by("-started_at", "-pk"):
        start = participant.consented_at or participant.started_at
        duration = participant.finished_at - start if participant.finished_at else None
        params = participant.recruitment_params or {}
        total = len(participant.schedule or [])
        rows.append(
            RosterRow(
                participant=participant,
                status=_status(participant),
                duration=duration,
                device=device_of(participant.user_agent),
                # reached is the next page to show: past the last one once finished.
                pages=gettext("%(reached)d of %(total)d")
                % {"reached": min(participant.reached, total), "total": total},
                recruitment_id=next(iter(params.values()), "") if params else "",
                reasons=tuple(reasons.get(str(participant.pk), ())),
            )
        )
    return rows, problem
