"""Record a researcher's review of participants: approved, or rejected from analysis."""

from django.db import transaction

from studyplatform.models import Participant, Study


def do_review_participants(study: Study, participant_ids, review: str) -> int:
    """Set the review of *study*'s participants in *participant_ids*; return how many.

    A rejected participant is flagged ``excluded`` in the export, so every analysis
    leaves them out, and no longer counts towards the study's target N.
    """
    if review not in Participant.Review.values:
        raise ValueError(f"Unknown review {review!r}.")
    with transaction.atomic(durable=True):
        return Participant.objects.filter(study=study, pk__in=list(participant_ids)).update(
            review=review
        )
