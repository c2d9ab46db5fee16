"""Enroll participants in a study."""

from collections.abc import Mapping

from django.core.exceptions import ValidationError
from django.db import transaction

from studyplatform.models import Participant, Study

# Longest recruitment parameter kept, in characters: ids from recruitment services are
# short; anything longer is not an id and is not stored.
MAX_PARAM_LENGTH = 200
MAX_PARAMS = 20


def clean_recruitment_params(params: Mapping[str, str]) -> dict[str, str]:
    """Return the URL parameters worth keeping (e.g. PROLIFIC_PID), bounded in size."""
    kept: dict[str, str] = {}
    for name, value in params.items():
        if len(kept) >= MAX_PARAMS:
            break
        if not name or len(name) > 64 or len(value) > MAX_PARAM_LENGTH:
            continue
        kept[name] = value
    return kept


def do_enroll_participant(
    study: Study, *, recruitment_params: Mapping[str, str] | None = None, user_agent: str = ""
) -> Participant:
    """Create a participant with a fresh token and seed in a pilot or open study."""
    if not study.is_accepting_participants:
        raise ValidationError(f"The study “{study.title}” is not taking participants now.")
    with transaction.atomic():
        return Participant.objects.create(
            study=study,
            recruitment_params=clean_recruitment_params(recruitment_params or {}),
            is_pilot=study.status == Study.Status.PILOT,
            language=(
                Participant.Language.ASL_ENGLISH
                if study.asl_first
                else Participant.Language.ENGLISH
            ),
            user_agent=user_agent[:400],
        )
