"""Let a participant stop and withdraw: everything they gave is deleted, at their word.

The consent says participants may stop at any time; before this only a researcher's
deletion withdrew their data. The link is on every page; a confirmation page asks once
(POST, CSRF-protected) and the same action as the researcher's deletion carries it out
(:func:`~studyplatform.actions.do_withdraw_participant`, logged with no researcher).
"""

from django.http import HttpRequest, HttpResponse
from django.shortcuts import render
from django.utils.translation import gettext
from django.views.decorators.cache import never_cache
from django.views.decorators.http import require_http_methods

from studyplatform.actions import do_withdraw_participant
from studyplatform.lib import participant_by_token
from studyplatform.views.language import in_study_language, speak
from studyplatform.views.participate import forget_in_browser

WITHDRAWN_BY_PARTICIPANT = "withdrawn by the participant"


@never_cache
@require_http_methods(["GET", "POST"])
@in_study_language
def withdraw(request: HttpRequest, token: str) -> HttpResponse:
    """Ask a participant to confirm (GET); withdraw them and delete their answers (POST)."""
    participant = participant_by_token(token)
    if participant is None:
        return render(
            request,
            "studyplatform/participate/problem.html",
            {"message": gettext("This link is not valid (or its answers were already withdrawn).")},
            status=404,
        )
    speak(request, participant.study)
    study = participant.study
    if request.method == "GET":
        return render(
            request,
            "studyplatform/participate/withdraw.html",
            {"participant": participant, "study": study},
        )
    do_withdraw_participant(participant, by=None, reason=WITHDRAWN_BY_PARTICIPANT)
    # The withdrawal forgets the participant in stored sessions; this request's own
    # session is saved after it and must not write the token back.
    forget_in_browser(request, study.slug, token)
    return render(request, "studyplatform/participate/withdrawn.html", {"study": study})
