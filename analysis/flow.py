"""Account for every participant: how many started, consented, finished, were excluded
and why, and were analysed (a CONSORT-style flow; Schulz, Altman & Moher 2010)."""

import dataclasses
from collections.abc import Mapping

import pandas as pd

from analysis.results import ExclusionReport, Result
from analysis.tidy import split_flags


@dataclasses.dataclass(frozen=True)
class ParticipantFlow(Result):
    """Participants at each stage of a study, and the exclusions between them.

    *started*, *consented* and *finished* come from the study's own participant records
    when the platform passes them (*source* ``"participant records"``); from a response
    table alone they count the participants with any answer, who all consented, and those
    not flagged incomplete (*source* ``"response table"``: who started and answered
    nothing is not in it). *excluded* counts each rule's participants (one participant
    may be excluded for several); *analysed* are those left.
    """

    started: int
    consented: int
    finished: int
    excluded: dict[str, int]
    excluded_participants: int
    analysed: int
    source: str

    def apa(self) -> str:
        reasons = ", ".join(f"{n} {reason}" for reason, n in self.excluded.items())
        text = (
            f"Of {self.started} participants who started, {self.consented} consented and "
            f"{self.finished} finished"
        )
        if self.excluded_participants:
            text += f"; {self.excluded_participants} were excluded ({reasons})"
        return f"{text}; {self.analysed} were analysed"


def participant_flow(
    frame: pd.DataFrame, exclusions: ExclusionReport, records: Mapping[str, int] | None = None
) -> ParticipantFlow:
    """Return the participant flow of *frame* (the whole response table) and its
    *exclusions*; *records* (``started``, ``consented``, ``finished``) are the study's own
    counts, which include participants who left before answering anything."""
    if records is not None:
        counts = {name: int(records[name]) for name in ("started", "consented", "finished")}
        source = "participant records"
    else:
        answered = frame["participant"].astype(str)
        incomplete = frame["flags"].map(lambda cell: "incomplete" in split_flags(cell))
        everyone = int(answered.nunique())
        counts = {
            "started": everyone,
            "consented": everyone,
            "finished": everyone - int(answered[incomplete].nunique()),
        }
        source = "response table"
    return ParticipantFlow(
        **counts,
        excluded=dict(exclusions.excluded_by_reason),
        excluded_participants=exclusions.participants_total - exclusions.participants_included,
        analysed=exclusions.participants_included,
        source=source,
    )
