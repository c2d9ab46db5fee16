"""The researcher's main page: a study with its conditions, items, questions, blocks and trials."""

import io
import tempfile
import zipfile

from django import forms
from django.contrib import admin, messages
from django.db import models
from django.db.models import Count
from django.forms import Textarea, TextInput
from django.http import Http404, HttpRequest, HttpResponse, JsonResponse
from django.shortcuts import redirect
from django.template.response import TemplateResponse
from django.urls import path, reverse
from django.utils.html import format_html
from django.utils.translation import gettext, gettext_lazy

from studyplatform.actions import StudyImportError, do_duplicate_study, do_import_study
from studyplatform.actions.design import do_add_default_options
from studyplatform.admin.builder import StudyDesignMixin
from studyplatform.admin.conditions import english_description
from studyplatform.admin.forms import StudyForm, StudyImportForm, TrialForm
from studyplatform.admin.generate import StudyGenerateMixin
from studyplatform.admin.permissions import DesignLockMixin, StudyInline, StudyScopedMixin
from studyplatform.admin.power import StudyPowerMixin
from studyplatform.admin.prompts import AslVideoInline, StudyAslMixin
from studyplatform.admin.recordings import StudyRecordingsMixin
from studyplatform.admin.results import StudyResultsMixin
from studyplatform.admin.roster import StudyRosterMixin
from studyplatform.admin.uploads import StudyUploadsMixin
from studyplatform.lib import exchange
from studyplatform.lib.asl import study_prompts
from studyplatform.lib.bundle import definition_json, write_bundle
from studyplatform.lib.preview import build_preview
from studyplatform.lib.stimuli import describe_identical, identical_clips
from studyplatform.models import Block, Condition, Item, Question, SignedTemplate, Study, Trial

# Compact cells keep the study page within the window; each object's page has the room.
COMPACT_TEXT = {
    models.TextField: {"widget": Textarea(attrs={"rows": 2, "cols": 20})},
    models.CharField: {"widget": TextInput(attrs={"size": 14})},
    models.SlugField: {"widget": TextInput(attrs={"size": 14})},
}


class ConditionInline(DesignLockMixin, StudyInline):
    formfield_overrides = COMPACT_TEXT
    model = Condition
    # The techniques are set field by field on each condition's page (its change link).
    fields = ("position", "key", "label", "source", "is_simulated", "compares")
    readonly_fields = ("compares",)
    verbose_name_plural = gettext_lazy("conditions (open one to set its techniques field by field)")

    @admin.display(description=gettext_lazy("What it compares"))
    def compares(self, obj: Condition) -> str:
        return english_description(obj)


class ItemInline(DesignLockMixin, StudyInline):
    model = Item
    formfield_overrides = COMPACT_TEXT
    fields = ("position", "key", "kind", "text", "target_text", "is_practice")


class QuestionInline(DesignLockMixin, StudyInline):
    model = Question
    formfield_overrides = COMPACT_TEXT
    fields = ("position", "key", "kind", "text", "required", "allow_no_difference")


class BlockInline(DesignLockMixin, StudyInline):
    formfield_overrides = COMPACT_TEXT
    model = Block
    fields = ("position", "key", "kind", "title", "randomize_order")


class TrialInline(DesignLockMixin, StudyInline):
    formfield_overrides = COMPACT_TEXT
    model = Trial
    verbose_name_plural = gettext_lazy(
        "trials (pages; the design builder makes them, edit one here)"
    )
    form = TrialForm
    fields = (
        "block",
        "key",
        "kind",
        "item",
        "condition_a",
        "condition_b",
        "is_attention_check",
    )
    classes = ("collapse",)


def _definition_filename(study: Study) -> str:
    return f"{study.slug}.study.json"


def _definition_json(study: Study) -> str:
    return definition_json(exchange.export_study(study))


@admin.register(Study)
class StudyAdmin(
    StudyGenerateMixin,
    StudyDesignMixin,
    StudyRosterMixin,
    StudyResultsMixin,
    StudyPowerMixin,
    StudyAslMixin,
    StudyRecordingsMixin,
    StudyUploadsMixin,
    StudyScopedMixin,
    admin.ModelAdmin,
):
    study_path = ""
    form = StudyForm
    list_display = (
        "title",
        "slug",
        "status",
        "asl_first",
        "condition_count",
        "trial_count",
        "participant_count",
        "created_at",
    )
    list_filter = ("status", "asl_first", "one_sitting")
    search_fields = ("title", "slug", "description")
    prepopulated_fields = {"slug": ("title",)}
    date_hierarchy = "created_at"
    # A redirect URL typed without a scheme means https (Django 6's default already).
    formfield_overrides = {models.URLField: {"assume_scheme": "https"}}
    inlines = (
        ConditionInline,
        ItemInline,
        QuestionInline,
        BlockInline,
        TrialInline,
        AslVideoInline,
    )
    actions = ("generate_stimuli", "duplicate_studies", "export_studies")
    fieldsets = (
        (None, {"fields": ("title", "slug", "status", "owner", "participant_link", "version_of")}),
        (
            gettext_lazy("Language"),
            {
                "fields": (
                    "language",
                    "follow_browser_language",
                    "sign_language",
                    "manual_alphabet",
                    "asl_first",
                    "allow_english_only",
                    "signed_templates",
                )
            },
        ),
        (
            gettext_lazy("What participants read"),
            {"fields": ("description", "consent_text", "consent_mode", "thank_you_text")},
        ),
        (
            gettext_lazy("Completion"),
            {"fields": ("completion_code", "unique_completion_codes", "redirect_url")},
        ),
        (gettext_lazy("Privacy"), {"fields": ("personal_data_retention_days",)}),
        (
            gettext_lazy("Rules"),
            {
                "fields": (
                    ("clip_width", "clip_height"),
                    "allowed_devices",
                    "phone_clips_side_by_side",
                    "one_sitting",
                    "shared_computer",
                    "time_limit_minutes",
                    "target_n",
                    "allow_back",
                    "replay_limit",
                    "require_full_view",
                    "randomize_positions",
                    "rotate_conditions",
                    "allow_identical_clips",
                )
            },
        ),
    )

    def get_queryset(self, request: HttpRequest):
        return (
            super()
            .get_queryset(request)
            .annotate(
                _conditions=Count("conditions", distinct=True),
                _trials=Count("trials", distinct=True),
                _participants=Count("participants", distinct=True),
            )
        )

    @admin.display(description=gettext_lazy("conditions"), ordering="_conditions")
    def condition_count(self, study: Study) -> int:
        return study._conditions

    @admin.display(description=gettext_lazy("trials"), ordering="_trials")
    def trial_count(self, study: Study) -> int:
        return study._trials

    @admin.display(description=gettext_lazy("participants"), ordering="_participants")
    def participant_count(self, study: Study) -> int:
        return study._participants

    def get_list_display(self, request: HttpRequest):
        if request.user.is_superuser:
            return (*self.list_display, "owner")
        return self.list_display

    def get_list_filter(self, request: HttpRequest):
        if request.user.is_superuser:
            return (*self.list_filter, "owner")
        return self.list_filter

    def get_readonly_fields(self, request: HttpRequest, obj: Study | None = None):
        own = () if request.user.is_superuser else ("owner",)
        # Which clips a participant sees follows from these; a locked design keeps them.
        locked = ("rotate_conditions", "randomize_positions") if obj and obj.design_locked else ()
        return (*own, *locked, "participant_link", "version_of")

    @admin.display(description=gettext_lazy("version"))
    def version_of(self, study: Study) -> str:
        """Say which version this is and what it was made from."""
        if study.previous_version is None:
            return str(study.version)
        url = reverse("admin:studyplatform_study_change", args=[study.previous_version.pk])
        return format_html(
            gettext('%(version)s (made from <a href="{}">{}</a>)') % {"version": study.version},
            url,
            study.previous_version.title,
        )

    @admin.display(description=gettext_lazy("participant link"))
    def participant_link(self, study: Study) -> str:
        """Show the link to send participants (recruitment services append their ids)."""
        if study.pk is None:
            return gettext("Save the study first.")
        url = reverse("study_welcome", args=[study.slug])
        return format_html(
            gettext(
                '<a href="{}" target="_blank" rel="noopener">{}</a> on this server'
                '<div class="help">Send this link to participants; parameters such as '
                "<code>?PROLIFIC_PID=…</code> are kept. It works while the study is in pilot "
                "or open.</div>"
            ),
            url,
            url,
        )

    def change_view(self, request: HttpRequest, object_id: str, form_url="", extra_context=None):
        """Show the study; warn first of identical clips and of ASL first with nothing signed."""
        study = self.get_object(request, object_id) if request.method == "GET" else None
        if study is not None and not study.allow_identical_clips:
            identical = identical_clips(study)
            if identical:
                messages.warning(request, describe_identical(identical))
        if study is not None and study.asl_first:
            prompts = study_prompts(study)
            if prompts and not any(p.video for p in prompts):
                messages.warning(
                    request,
                    gettext(
                        "Signing first is on, but none of the %(count)d texts participants "
                        "read has a signed video: they see the written text only. Add videos "
                        "on the ASL videos page, or attach signed templates under Language."
                    )
                    % {"count": len(prompts)},
                )
        return super().change_view(request, object_id, form_url, extra_context)

    def formfield_for_manytomany(self, db_field, request: HttpRequest, **kwargs):
        if db_field.name == "signed_templates":
            # Check boxes, not Django's two-list filter widget: its search icons carry
            # ARIA attributes a span may not have (axe-core), and a lab has few templates.
            kwargs["widget"] = forms.CheckboxSelectMultiple
            if not request.user.is_superuser:
                kwargs["queryset"] = SignedTemplate.objects.filter(owner=request.user)
        return super().formfield_for_manytomany(db_field, request, **kwargs)

    def get_changeform_initial_data(self, request: HttpRequest):
        return {**super().get_changeform_initial_data(request), "owner": request.user.pk}

    def save_model(self, request: HttpRequest, obj: Study, form, change: bool) -> None:
        if not change and not request.user.is_superuser:
            obj.owner = request.user
        super().save_model(request, obj, form, change)

    def save_formset(self, request: HttpRequest, form, formset, change: bool) -> None:
        super().save_formset(request, form, formset, change)
        if formset.model is Question:
            for question in formset.new_objects:
                do_add_default_options(question)

    def get_urls(self):
        own = [
            path(
                "import/",
                self.admin_site.admin_view(self.import_view),
                name="studyplatform_study_import",
            ),
            path(
                "parameters-schema.json",
                self.admin_site.admin_view(self.parameters_schema_view),
                name="studyplatform_study_parameters_schema",
            ),
            path(
                "<path:object_id>/export/",
                self.admin_site.admin_view(self.export_view),
                name="studyplatform_study_export",
            ),
            path(
                "<path:object_id>/preview/",
                self.admin_site.admin_view(self.preview_view),
                name="studyplatform_study_preview",
            ),
        ]
        return (
            own
            + self.generate_urls()
            + self.design_urls()
            + self.roster_urls()
            + self.results_urls()
            + self.power_urls()
            + self.asl_urls()
            + self.recordings_urls()
            + self.uploads_urls()
            + super().get_urls()
        )

    def _get_visible_study(self, request: HttpRequest, object_id: str) -> Study:
        study = self.get_object(request, object_id)
        if study is None or not self.has_view_permission(request, study):
            raise Http404("No such study.")
        return study

    def export_view(self, request: HttpRequest, object_id: str) -> HttpResponse:
        """Download the study's definition as JSON, or with ?media=1 as a bundle (zip)."""
        study = self._get_visible_study(request, object_id)
        if request.GET.get("media") == "1":
            with tempfile.SpooledTemporaryFile(max_size=50 * 1024 * 1024) as buffer:
                write_bundle(exchange.export_study(study), buffer)
                buffer.seek(0)
                response = HttpResponse(buffer.read(), content_type="application/zip")
            response["Content-Disposition"] = f'attachment; filename="{study.slug}.study.zip"'
            return response
        response = HttpResponse(_definition_json(study), content_type="application/json")
        response["Content-Disposition"] = f'attachment; filename="{_definition_filename(study)}"'
        return response

    def _page(self, request: HttpRequest, template: str, title: str, **context) -> TemplateResponse:
        """Render one of the study admin's own pages with the admin's context."""
        context = {
            **self.admin_site.each_context(request),
            "opts": self.opts,
            "title": title,
            **context,
        }
        return TemplateResponse(request, f"admin/studyplatform/study/{template}", context)

    def preview_view(self, request: HttpRequest, object_id: str) -> TemplateResponse:
        """Show every page of the study as a participant would see it, answers disabled."""
        study = self._get_visible_study(request, object_id)
        return self._page(
            request,
            "preview.html",
            gettext("Preview of “%(title)s”") % {"title": study.title},
            study=study,
            preview=build_preview(study),
        )

    def parameters_schema_view(self, request: HttpRequest) -> HttpResponse:
        """Serve the JSON Schema of condition and item parameters."""
        return JsonResponse(exchange.parameters_schema(), json_dumps_params={"indent": 2})

    def import_view(self, request: HttpRequest) -> HttpResponse:
        """Create a study from an uploaded definition file."""
        if not self.has_add_permission(request):
            raise Http404("You cannot add studies.")
        form = StudyImportForm(request.POST or None, request.FILES or None)
        if request.method == "POST" and form.is_valid():
            definition, files = form.cleaned_data["definition"]
            section = definition.get("study") if isinstance(definition, dict) else None
            original = section.get("title") if isinstance(section, dict) else None
            # A definition carries no participants: it arrives as a draft to pilot and
            # open, and named apart from a study of the same title the researcher has.
            title = None
            if isinstance(original, str) and (
                Study.objects.filter(owner=request.user, title=original).exists()
            ):
                title = (gettext("%(title)s (imported)") % {"title": original})[:200]
            try:
                result = do_import_study(
                    definition,
                    owner=request.user,
                    slug=form.cleaned_data["slug"] or None,
                    title=title,
                    status=Study.Status.DRAFT,
                    files=files,
                )
            except StudyImportError as error:
                form.add_error(
                    "definition", gettext("Not imported: %(problem)s") % {"problem": error}
                )
            else:
                messages.success(
                    request, gettext("Imported “%(title)s”.") % {"title": result.study.title}
                )
                for warning in result.warnings:
                    messages.warning(request, warning)
                return redirect(reverse("admin:studyplatform_study_change", args=[result.study.pk]))
        page = self._page(request, "import.html", gettext("Import a study definition"), form=form)
        if request.method == "POST":
            page.status_code = 400  # refused: the form says why
        return page

    @admin.action(description=gettext_lazy("Duplicate the selected studies (as drafts)"))
    def duplicate_studies(self, request: HttpRequest, queryset) -> None:
        for study in queryset:
            copy = do_duplicate_study(study, owner=request.user)
            messages.success(
                request,
                format_html(
                    gettext("Created <a href='{}'>{}</a>."),
                    reverse("admin:studyplatform_study_change", args=[copy.pk]),
                    copy.title,
                ),
            )

    @admin.action(description=gettext_lazy("Export the selected studies as JSON"))
    def export_studies(self, request: HttpRequest, queryset) -> HttpResponse:
        studies = list(queryset)
        if len(studies) == 1:
            return self.export_view(request, str(studies[0].pk))
        buffer = io.BytesIO()
        with zipfile.ZipFile(buffer, "w", zipfile.ZIP_DEFLATED) as archive:
            for study in studies:
                archive.writestr(_definition_filename(study), _definition_json(study))
        response = HttpResponse(buffer.getvalue(), content_type="application/zip")
        response["Content-Disposition"] = 'attachment; filename="studies.zip"'
        return response
