"""Which clips a participant is shown on a page: their schedule entry, sides and rows."""

from collections.abc import Mapping

from studyplatform.models import Condition, Participant, Trial


def schedule_entry(participant: Participant, trial: Trial) -> dict | None:
    """Return the participant's schedule entry of *trial*, or None if they are not shown it."""
    for entry in participant.schedule:
        if isinstance(entry, dict) and entry.get("trial") == trial.key:
            return entry
    return None


def presented_conditions(
    participant: Participant, trial: Trial, conditions: Mapping[str, Condition] | None = None
) -> tuple[Condition | None, Condition | None]:
    """Return the conditions shown as Clip 1 and Clip 2 to *participant* on *trial*.

    The participant's stored schedule says whether the trial's clips were swapped
    (``"swap": true``) and, under Latin-square rotation, which conditions were shown
    (``"a"``, ``"b"``); without an entry the trial's own clips show in order.
    *conditions* (the study's, by key) saves a query per call.
    """
    entry = schedule_entry(participant, trial) or {}
    first, second = trial.condition_a, trial.condition_b
    if "a" in entry:
        if conditions is None:
            keys = [entry["a"], entry.get("b")]
            found = Condition.objects.filter(study_id=trial.study_id, key__in=keys)
            conditions = {condition.key: condition for condition in found}
        first, second = conditions.get(entry["a"]), conditions.get(entry.get("b"))
    if entry.get("swap"):
        return second, first
    return first, second
