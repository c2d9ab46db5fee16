"""The study's results page in the admin: live analysis, exclusions, downloads."""

from django.http import HttpRequest, HttpResponse
from django.template.response import TemplateResponse
from django.urls import path
from django.utils.translation import gettext, gettext_lazy

from analysis import TidyFormatError, results_json
from studyplatform.admin.forms import ResultsForm
from studyplatform.lib.results import StudyResults, analyse_study, figure_images, report_archive
from studyplatform.lib.signed import signed_summary
from studyplatform.models import Block, Question, Study

# What each of the report's figures (analysis.figures, by file name) shows, for its alt.
FIGURE_DESCRIPTIONS = {
    "participant_flow": gettext_lazy(
        "Participant flow: started, consented, finished, excluded by each rule, analysed"
    ),
    "condition_rates": gettext_lazy("Each condition's win rate, with its interval"),
    "pairwise_matrix": gettext_lazy("How often each condition was chosen over each other"),
    "ratings_boxplots": gettext_lazy("Each item's ratings per condition, as box plots"),
}


def _signed_summary(study: Study) -> dict[str, float] | None:
    """Return how many signed answers the "everything" zip carries, and their MB."""
    count, size = signed_summary(study)
    return {"count": count, "mb": size / 1e6} if count else None


class StudyResultsMixin:
    """Add results, CSV and report download pages to the study admin."""

    def results_urls(self):
        view = self.admin_site.admin_view
        return [
            path(
                "<path:object_id>/results/",
                view(self.results_view),
                name="studyplatform_study_results",
            ),
            path(
                "<path:object_id>/results/responses.csv",
                view(self.results_csv_view),
                name="studyplatform_study_results_csv",
            ),
            path(
                "<path:object_id>/results/report.zip",
                view(self.results_zip_view),
                {"everything": False},
                name="studyplatform_study_results_report",
            ),
            path(
                "<path:object_id>/results/everything.zip",
                view(self.results_zip_view),
                {"everything": True},
                name="studyplatform_study_results_everything",
            ),
        ]

    def _results(self, request: HttpRequest, study: Study) -> tuple[ResultsForm, StudyResults]:
        demographic = (
            Question.objects.filter(
                study=study, trials__block__kind=Block.Kind.DEMOGRAPHICS, is_personal=False
            )
            .distinct()
            .prefetch_related("options")
            .order_by("position", "pk")
        )
        form = ResultsForm(request.GET, demographic_questions=demographic)
        return form, analyse_study(study, form.options())

    def results_view(self, request: HttpRequest, object_id: str) -> TemplateResponse:
        """Show the study's results as they stand, with exclusion controls."""
        study = self._get_visible_study(request, object_id)
        form, results = None, None
        error = None
        try:
            form, results = self._results(request, study)
        except TidyFormatError as problem:
            error = str(problem)
        context = {
            **self.admin_site.each_context(request),
            "opts": self.opts,
            "study": study,
            "title": gettext("Results of “%(title)s”") % {"title": study.title},
            "form": form,
            "error": error,
            "results": None
            if results is None or results.report is None
            else results_json(results.report),
            "report": None if results is None else results.report,
            "figures": {} if results is None else figure_images(results),
            "figure_descriptions": FIGURE_DESCRIPTIONS,
            "query": request.GET.urlencode(),
            "signed": _signed_summary(study),
            "refresh": request.GET.get("refresh") == "1",
        }
        return TemplateResponse(request, "admin/studyplatform/study/results.html", context)

    def results_csv_view(self, request: HttpRequest, object_id: str) -> HttpResponse:
        """Download every response of the study as tidy CSV (flags included, nothing dropped)."""
        from studyplatform.lib.export import tidy_csv

        study = self._get_visible_study(request, object_id)
        response = HttpResponse(tidy_csv(study), content_type="text/csv; charset=utf-8")
        response["Content-Disposition"] = f'attachment; filename="{study.slug}-responses.csv"'
        return response

    def results_zip_view(self, request: HttpRequest, object_id: str, everything: bool):
        """Download the report (and with *everything*, the data and study definition)."""
        study = self._get_visible_study(request, object_id)
        _, results = self._results(request, study)
        name = f"{study.slug}-{'everything' if everything else 'report'}.zip"
        videos = request.GET.get("videos") != "0"
        response = HttpResponse(
            report_archive(study, results, everything=everything, videos=videos),
            content_type="application/zip",
        )
        response["Content-Disposition"] = f'attachment; filename="{name}"'
        return response
