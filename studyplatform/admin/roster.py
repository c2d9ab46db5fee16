"""The study's participants page: who took part, how, why excluded; approve or reject."""

from django.contrib import messages
from django.http import HttpRequest, HttpResponse
from django.shortcuts import redirect
from django.urls import path, reverse
from django.utils.translation import gettext, ngettext

from studyplatform.actions import do_review_participants
from studyplatform.admin.forms import ResultsForm
from studyplatform.lib.roster import roster
from studyplatform.models import Participant

REVIEWS = {
    "approve": Participant.Review.APPROVED,
    "reject": Participant.Review.REJECTED,
    "reset": Participant.Review.PENDING,
}


class StudyRosterMixin:
    """Add the participants page to the study admin."""

    def roster_urls(self):
        return [
            path(
                "<path:object_id>/participants/",
                self.admin_site.admin_view(self.roster_view),
                name="studyplatform_study_participants",
            )
        ]

    def roster_view(self, request: HttpRequest, object_id: str) -> HttpResponse:
        """List the participants with the results page's exclusion rules; review on POST."""
        study = self._get_visible_study(request, object_id)
        can_review = self.has_change_permission(request, study)
        if request.method == "POST" and can_review:
            review = REVIEWS.get(request.POST.get("review", ""))
            # A participant's number: a 64-bit integer (a longer one names nobody).
            chosen = [
                v
                for v in request.POST.getlist("participant")
                if v.isascii() and v.isdigit() and len(v) <= 18
            ]
            if review is None or not chosen:
                messages.error(request, gettext("Tick participants and choose Approve or Reject."))
            else:
                count = do_review_participants(study, chosen, review)
                messages.success(
                    request,
                    ngettext(
                        "%(count)d participant: %(review)s.",
                        "%(count)d participants: %(review)s.",
                        count,
                    )
                    % {"count": count, "review": str(review.label).lower()},
                )
            query = request.POST.get("query", "")
            url = reverse("admin:studyplatform_study_participants", args=[study.pk])
            return redirect(f"{url}?{query}" if query else url)
        form = ResultsForm(request.GET, demographic_questions=[])
        rows, problem = roster(study, form.options().exclusions)
        finished = sum(r.status == "complete" and r.participant.review != "rejected" for r in rows)
        return self._page(
            request,
            "participants.html",
            gettext("Participants of “%(title)s”") % {"title": study.title},
            study=study,
            rows=rows,
            problem=problem,
            form=form,
            can_review=can_review,
            finished=finished,
            query=request.GET.urlencode(),
        )
