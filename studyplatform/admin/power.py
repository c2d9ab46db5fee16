"""The "Plan sample size" page: simulate the study's power from its pilot responses."""

import base64
import tempfile
from pathlib import Path

import pandas as pd
from django import forms
from django.http import HttpRequest
from django.template.response import TemplateResponse
from django.urls import path
from django.utils.translation import gettext, gettext_lazy

from analysis import ExclusionRules, TidyFormatError, apply_exclusions, check_responses
from analysis.power import design_from_responses, power_curve
from analysis.power.plan import effects_for, power_figure
from studyplatform.lib.export import tidy_rows
from studyplatform.models import Study


class PlanForm(forms.Form):
    """What to plan: the kind of answer, the range of N and how many simulations."""

    kind = forms.ChoiceField(
        label=gettext_lazy("Kind"),
        choices=[
            ("pairwise", gettext_lazy("pairwise choices")),
            ("rating", gettext_lazy("ratings of one question")),
        ],
        initial="pairwise",
        help_text=gettext_lazy(
            "Which planned test to simulate: the mixed Bradley–Terry model and "
            "binomial tests, or the ordinal mixed model and paired t-tests."
        ),
    )
    question = forms.CharField(
        label=gettext_lazy("Question"),
        required=False,
        help_text=gettext_lazy("The rated question's key (for ratings only)."),
    )
    smallest = forms.IntegerField(
        min_value=2, max_value=1000, initial=10, label=gettext_lazy("From N")
    )
    largest = forms.IntegerField(
        min_value=2, max_value=1000, initial=60, label=gettext_lazy("To N")
    )
    step = forms.IntegerField(min_value=1, max_value=500, initial=10, label=gettext_lazy("Step"))
    simulations = forms.IntegerField(
        label=gettext_lazy("Simulations"),
        min_value=10,
        max_value=500,
        initial=100,
        help_text=gettext_lazy("Simulated studies per N; 100 gives power ± 5 points, 400 ± 2.5."),
    )
    seed = forms.IntegerField(
        label=gettext_lazy("Seed"),
        min_value=0,
        initial=1,
        help_text=gettext_lazy("Repeat a plan with its seed."),
    )

    def clean(self):
        data = super().clean()
        if data.get("smallest") and data.get("largest") and data["largest"] < data["smallest"]:
            raise forms.ValidationError(gettext("“To N” must not be below “From N”."))
        if data.get("kind") == "rating" and not data.get("question"):
            raise forms.ValidationError(gettext("Name the rated question to plan ratings."))
        sizes = range(data.get("smallest", 2), data.get("largest", 2) + 1, data.get("step", 1))
        if len(sizes) > 12:
            raise forms.ValidationError(gettext("Plan at most 12 values of N at once."))
        return data


class StudyPowerMixin:
    """Add the "Plan sample size" page to the study admin."""

    def power_urls(self):
        return [
            path(
                "<path:object_id>/plan/",
                self.admin_site.admin_view(self.power_view),
                name="studyplatform_study_plan",
            )
        ]

    def power_view(self, request: HttpRequest, object_id: str) -> TemplateResponse:
        """Simulate the study's power from its pilot (a GET form; nothing is saved)."""
        study = self._get_visible_study(request, object_id)
        form = PlanForm(request.GET if "kind" in request.GET else None)
        curve = figure = error = None
        if study.status != Study.Status.PILOT:
            error = gettext(
                "Sample-size planning uses a pilot: set the study's status to Pilot first."
            )
        elif form.is_valid():
            try:
                curve, figure = self._plan(study, form.cleaned_data)
            except (TidyFormatError, ValueError) as problem:
                error = str(problem)
        context = {
            **self.admin_site.each_context(request),
            "opts": self.opts,
            "study": study,
            "title": gettext("Plan sample size for “%(title)s”") % {"title": study.title},
            "form": form,
            "curve": curve,
            "table": None if curve is None else curve.table().to_dict("records"),
            "figure": figure,
            "requirements": [] if curve is None else [curve.apa(test) for test in curve.tests],
            "error": error,
        }
        return TemplateResponse(request, "admin/studyplatform/study/plan.html", context)

    def _plan(self, study: Study, options: dict):
        columns, rows = tidy_rows(study)
        frame = pd.DataFrame(list(rows), columns=columns, dtype=str)
        if frame.empty:
            raise TidyFormatError("the pilot has no responses yet.")
        table = check_responses(frame, source=f"{study.slug} pilot")
        pilot, _ = apply_exclusions(table, ExclusionRules(pilot=False))
        design = design_from_responses(pilot, options["kind"], options["question"])
        effects = effects_for(pilot, design, source=f"{study.slug} pilot")
        sizes = range(options["smallest"], options["largest"] + 1, options["step"])
        curve = power_curve(
            design,
            effects,
            sizes,
            simulations=options["simulations"],
            seed=options["seed"],
            workers=1,
        )
        with tempfile.TemporaryDirectory() as folder:
            image = Path(folder) / "power.png"
            power_figure(curve, image)
            encoded = base64.b64encode(image.read_bytes()).decode("ascii")
        return curve, f"data:image/png;base64,{encoded}"
