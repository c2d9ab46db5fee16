"""Derive per-trial quality data from what participants' browsers logged (media events).

For each participant × trial: where the page came in their schedule, when it was first
shown, how long it was on screen, how often each clip was played and whether it played
to its end, playback errors, the viewport; and whether the answer came before the
page's clips had ended (the speeder rule). All times are the browser's clock, so
durations never mix the participant's clock with the server's.
"""

import json
import re
from collections import defaultdict
from dataclasses import dataclass, field
from datetime import UTC, datetime

from analysis.tidy import QUALITY_COLUMNS
from studyplatform.models import MediaEvent, Participant, Study

_PHONE = re.compile(r"Mobi|iPhone|Android.+Mobile", re.IGNORECASE)
_TABLET = re.compile(r"iPad|Tablet|Android", re.IGNORECASE)


def device_of(user_agent: str) -> str:
    """Return "phone", "tablet" or "desktop" from a browser's user agent ("" if unknown)."""
    if not user_agent:
        return ""
    if _PHONE.search(user_agent):
        return "phone"
    if _TABLET.search(user_agent):
        return "tablet"
    return "desktop"


@dataclass
class TrialQuality:
    """What one participant's browser logged on one trial's page."""

    first_shown_ms: float | None = None
    # Each showing of the page: when it was shown and when it left the screen (None
    # while it was the last thing logged).
    visits: list[list] = field(default_factory=list)
    on_page_ms: float = 0.0
    plays: dict[int, int] = field(default_factory=lambda: {1: 0, 2: 0})
    first_ended_ms: dict[int, float] = field(default_factory=dict)
    errors: int = 0
    viewport: str = ""


def _iso(client_ms: float | None) -> str:
    if client_ms is None:
        return ""
    return datetime.fromtimestamp(client_ms / 1000, tz=UTC).isoformat(timespec="milliseconds")


def _count_event(quality: TrialQuality, event, at: float) -> None:
    """Count one event of a page: a showing (the first one's viewport), a play, an end of a
    clip, an error."""
    if event.kind == MediaEvent.Kind.PAGE_SHOWN:
        quality.visits.append([at, None])
        if quality.first_shown_ms is None:
            quality.first_shown_ms = at
            size = event.detail or {}
            if "width" in size and "height" in size:
                quality.viewport = f"{size['width']}x{size['height']}"
    elif event.kind == MediaEvent.Kind.PLAY and event.clip_position in (1, 2):
        quality.plays[event.clip_position] += 1
    elif event.kind == MediaEvent.Kind.ENDED and event.clip_position in (1, 2):
        quality.first_ended_ms.setdefault(event.clip_position, at)
    elif event.kind == MediaEvent.Kind.ERROR:
        quality.errors += 1


def participant_quality(events) -> dict[int, TrialQuality]:
    """Return each trial's quality of one participant from their events (any order).

    A visit to a page lasts from its ``page_shown`` to the next page's ``page_shown``,
    the page being hidden, or the visit's last event; a page's time sums its visits.
    """
    by_trial: dict[int, TrialQuality] = defaultdict(TrialQuality)
    visit: tuple[int, float] | None = None
    last_ms: float | None = None

    def close(until_ms: float | None) -> None:
        if visit is not None and until_ms is not None:
            by_trial[visit[0]].on_page_ms += max(0.0, until_ms - visit[1])
            by_trial[visit[0]].visits[-1][1] = until_ms

    for event in sorted(events, key=lambda e: (e.client_time_ms or 0, e.pk or 0)):
        at = event.client_time_ms
        if event.kind in (MediaEvent.Kind.PAGE_SHOWN, MediaEvent.Kind.PAGE_HIDDEN):
            close(at)
            visit = None
        if event.trial_id is None or at is None:
            continue
        if event.kind == MediaEvent.Kind.PAGE_SHOWN:
            visit = (event.trial_id, at)
        _count_event(by_trial[event.trial_id], event, at)
        last_ms = at
    close(last_ms)
    return dict(by_trial)


def study_quality(study: Study) -> dict[int, dict[int, TrialQuality]]:
    """Return participant id → trial id → quality, for every participant of *study*."""
    events: dict[int, list] = defaultdict(list)
    rows = MediaEvent.objects.filter(participant__study=study).only(
        "pk", "participant_id", "trial_id", "kind", "clip_position", "client_time_ms", "detail"
    )
    for event in rows.iterator(chunk_size=2000):
        events[event.participant_id].append(event)
    return {participant: participant_quality(found) for participant, found in events.items()}


def page_orders(participant: Participant) -> dict[str, str]:
    """Return trial key → its page number in the participant's schedule (from 1)."""
    return {entry.get("trial"): str(n) for n, entry in enumerate(participant.schedule or [], 1)}


def quality_cells(
    participant: Participant,
    trial,
    quality: TrialQuality | None,
    rt_ms: int | None,
    answered_at: datetime | None,
    orders: dict[str, str],
    client_ms: int | None = None,
) -> dict[str, str]:
    """Return the quality columns of one answer (empty cells where nothing was logged).

    *orders* is the participant's :func:`page_orders`. The answer came before the end
    when a clip of the page had not yet ended, in this showing or an earlier one, at the
    answer's time on the browser's clock: *client_ms*, which the page sends with the
    answer, or for answers saved without it the showing the response time fits in (the
    last whose shown time plus *rt_ms* falls before it left the screen).
    """
    cells = dict.fromkeys(QUALITY_COLUMNS, "")
    cells.update(
        page_order=orders.get(trial.key, ""),
        answered_at="" if answered_at is None else answered_at.isoformat(timespec="seconds"),
        device=device_of(participant.user_agent),
    )
    if quality is None:
        return cells
    clips = (1, 2) if trial.condition_b_id else (1,) if trial.condition_a_id else ()
    cells.update(
        shown_at=_iso(quality.first_shown_ms),
        time_on_page_ms=str(round(quality.on_page_ms)),
        playback_errors=str(quality.errors),
        viewport=quality.viewport,
        replays=str(sum(max(0, quality.plays[c] - 1) for c in clips)),
    )
    for clip in clips:
        cells[f"clip{clip}_plays"] = str(quality.plays[clip])
        cells[f"clip{clip}_ended"] = "1" if clip in quality.first_ended_ms else "0"
    answered_ms = _answered_ms(quality, rt_ms, client_ms)
    if clips and answered_ms is not None:
        early = any(quality.first_ended_ms.get(c, float("inf")) > answered_ms for c in clips)
        cells["answered_before_end"] = "1" if early else "0"
    return cells


# An answer is saved while its page is on screen; this much slack allows for the
# page-hidden event being logged a moment before the last save.
_SLACK_MS = 1000.0


def _answered_ms(quality: TrialQuality, rt_ms: int | None, client_ms: int | None):
    """Return when the answer was given on the browser's clock (None if unknown)."""
    if client_ms is not None:
        return float(client_ms)
    if rt_ms is None or not quality.visits:
        return None
    fitting = [
        shown + rt_ms
        for shown, left in quality.visits
        if left is None or shown + rt_ms <= left + _SLACK_MS
    ]
    return fitting[-1] if fitting else quality.visits[-1][0] + rt_ms


EVENT_COLUMNS = (
    "participant",
    "trial",
    "clip",
    "kind",
    "media_time_s",
    "client_time_ms",
    "received_at",
    "detail",
)
PARTICIPANT_COLUMNS = (
    "participant",
    "is_pilot",
    "review",
    "language",
    "seed",
    "enrollment",
    "started_at",
    "consented_at",
    "finished_at",
    "device",
    "user_agent",
    "completion_code",
    "recruitment",
    "schedule",
)


def media_event_rows(study: Study):
    """Yield every media event of *study*'s participants as a row of EVENT_COLUMNS."""
    events = MediaEvent.objects.filter(participant__study=study).select_related("trial")
    events = events.order_by("participant_id", "client_time_ms", "pk")
    for event in events.iterator(chunk_size=2000):
        yield {
            "participant": str(event.participant_id),
            "trial": event.trial.key if event.trial else "",
            "clip": "" if event.clip_position is None else str(event.clip_position),
            "kind": event.kind,
            "media_time_s": "" if event.media_time_s is None else f"{event.media_time_s:g}",
            "client_time_ms": "" if event.client_time_ms is None else str(event.client_time_ms),
            "received_at": event.created_at.isoformat(timespec="milliseconds"),
            "detail": json.dumps(event.detail, ensure_ascii=False) if event.detail else "",
        }


def participant_rows(study: Study):
    """Yield each participant of *study* with their seed and schedule (PARTICIPANT_COLUMNS).

    The schedule is the exact sequence of pages (trial, sides swapped, rotated
    conditions) the seed and enrollment number drew. Personal answers are not included;
    the recruitment parameters are (``recruitment``, e.g. ``{"PROLIFIC_PID": …}``), since
    approving and paying participants needs them.
    """
    participants = study.participants.order_by("started_at", "pk")
    for enrollment, participant in enumerate(participants):
        times = {
            name: getattr(participant, name)
            for name in ("started_at", "consented_at", "finished_at")
        }
        yield {
            "participant": str(participant.pk),
            "is_pilot": str(int(participant.is_pilot)),
            "review": participant.review,
            "language": participant.language,
            "seed": str(participant.seed),
            "enrollment": str(enrollment),
            **{k: "" if v is None else v.isoformat(timespec="seconds") for k, v in times.items()},
            "device": device_of(participant.user_agent),
            "user_agent": participant.user_agent,
            "completion_code": participant.completion_code,
            "recruitment": json.dumps(participant.recruitment_params or {}, ensure_ascii=False),
            "schedule": json.dumps(participant.schedule, ensure_ascii=False),
        }
