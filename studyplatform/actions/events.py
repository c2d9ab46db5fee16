"""Log what participants did with the clips and pages: play, pause, seek, end, errors."""

from collections.abc import Sequence
from datetime import timedelta

from django.core.exceptions import ValidationError
from django.db import transaction
from django.utils import timezone

from studyplatform.lib.participants import PageRejected, page_trial
from studyplatform.lib.presentation import presented_conditions
from studyplatform.models import MediaEvent, Participant, Stimulus

MAX_EVENTS_PER_BATCH = 500
MAX_DETAIL_LENGTH = 500
# The largest magnitudes taken: a clip's time (a day, in s) and the page's clock
# (JavaScript's largest exact integer, in ms; it also fits the 64-bit column).
NUMBER_LIMITS = {"media_time_s": 86_400.0, "client_time_ms": 2.0**53}
# The last page's events reach the server just after its Next finished the study (the page
# sends them as it unloads); later than this, a finished participant's events are refused.
FINISHED_GRACE = timedelta(minutes=2)


class EventsRejected(ValidationError):
    """A batch of events with a malformed event; none of the batch was saved."""


def _kind_and_page(number: int, raw: object) -> tuple[str, int]:
    """Check one raw event's kind and page (a JSON object); EventsRejected names a problem."""
    if not isinstance(raw, dict):
        raise EventsRejected(f"Event {number} is not an object.")
    kind = raw.get("kind")
    if kind not in MediaEvent.Kind.values:
        raise EventsRejected(f"Event {number} has an unknown kind “{kind}”.")
    page = raw.get("page")
    if not isinstance(page, int) or isinstance(page, bool):
        raise EventsRejected(f"Event {number} names no page.")
    return kind, page


def _checked(number: int, raw: dict) -> dict:
    """Check the rest of one raw event's fields (its page is known); return them."""
    clip = raw.get("clip")
    # Exactly None, 1 or 2: 1.0 and True compare equal to 1 but index nothing.
    if not (clip is None or (type(clip) is int and clip in (1, 2))):
        raise EventsRejected(f"Event {number} names clip {clip!r}; a page has clips 1 and 2.")
    if not isinstance(raw.get("client_time_ms"), int | float):
        # The browser's clock tells a resent event from a new one (see do_log_media_events).
        raise EventsRejected(f"Event {number} has no client_time_ms.")
    detail = raw.get("detail") or {}
    if not isinstance(detail, dict) or len(str(detail)) > MAX_DETAIL_LENGTH:
        raise EventsRejected(f"Event {number}: the detail is not a small object.")
    fields = {"clip": clip, "detail": detail}
    for name in ("media_time_s", "client_time_ms"):
        fields[name] = _number(number, name, raw.get(name))
    return fields


def _number(number: int, name: str, value: object) -> float | None:
    """Return an event's optional number field, or EventsRejected naming it."""
    if value is not None and (not isinstance(value, int | float) or isinstance(value, bool)):
        raise EventsRejected(f"Event {number}: {name} is not a number.")
    # NaN and infinities compare false too; an integer beyond any float compares fine.
    if value is not None and not abs(value) <= NUMBER_LIMITS[name]:
        raise EventsRejected(f"Event {number}: {name} {value!r} is out of range.")
    return value


def _event(
    participant: Participant, number: int, raw: object, trials: dict, stimuli: dict
) -> MediaEvent:
    """Check one raw event (a JSON object) and return the unsaved row.

    *trials* (by page) and *stimuli* (by page and clip) remember lookups across a batch.
    """
    kind, page = _kind_and_page(number, raw)
    if page not in trials:
        try:
            trials[page] = page_trial(participant, page)
        except PageRejected as error:
            raise EventsRejected(f"Event {number}: {error.message}") from None
    trial = trials[page]
    fields = _checked(number, raw)
    clip = fields["clip"]
    if clip is not None and trial.item_id and (page, clip) not in stimuli:
        # A batch holds many events of the same clips.
        condition = presented_conditions(participant, trial)[clip - 1]
        stimuli[(page, clip)] = (
            Stimulus.objects.filter(condition=condition, item_id=trial.item_id).first()
            if condition is not None
            else None
        )
    client_ms = fields["client_time_ms"]
    return MediaEvent(
        participant=participant,
        trial=trial,
        stimulus=stimuli.get((page, clip)) if clip is not None and trial.item_id else None,
        clip_position=clip,
        kind=kind,
        media_time_s=fields["media_time_s"],
        client_time_ms=None if client_ms is None else int(client_ms),
        detail=fields["detail"],
    )


def do_log_media_events(participant: Participant, events: Sequence[object]) -> int:
    """Save a batch of events from the participant's browser; return how many were new.

    A batch sent again (its answer was lost on the way back) adds nothing: an event
    equal in kind, page, clip and browser time to a logged one is skipped. A finished
    participant's events are taken for FINISHED_GRACE after finishing, then refused.
    """
    if participant.is_finished and timezone.now() - participant.finished_at > FINISHED_GRACE:
        raise EventsRejected("This study is finished; nothing about it can change now.")
    if not isinstance(events, list | tuple):
        raise EventsRejected("Events come as a list.")
    if len(events) > MAX_EVENTS_PER_BATCH:
        raise EventsRejected(f"At most {MAX_EVENTS_PER_BATCH} events per batch.")
    trials: dict = {}
    stimuli: dict = {}
    rows = [
        _event(participant, number, raw, trials, stimuli) for number, raw in enumerate(events, 1)
    ]
    with transaction.atomic(durable=True):
        times = [row.client_time_ms for row in rows]
        seen = set()
        if times:
            seen = set(
                MediaEvent.objects.filter(
                    participant=participant,
                    client_time_ms__gte=min(times),
                    client_time_ms__lte=max(times),
                ).values_list("kind", "trial_id", "clip_position", "client_time_ms")
            )
        new = []
        for row in rows:
            key = (row.kind, row.trial_id, row.clip_position, row.client_time_ms)
            if key not in seen:
                seen.add(key)
                new.append(row)
        MediaEvent.objects.bulk_create(new)
    return len(new)
