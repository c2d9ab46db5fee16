"""Attach ASL videos to participant-facing text from the admin."""

from django import forms
from django.contrib import admin, messages
from django.contrib.contenttypes.admin import GenericTabularInline
from django.core.exceptions import PermissionDenied, ValidationError
from django.db.models import Count
from django.http import HttpRequest, HttpResponse, JsonResponse
from django.shortcuts import redirect
from django.urls import path
from django.utils.translation import gettext, gettext_lazy

from studyplatform.actions.prompts import do_attach_asl_video
from studyplatform.admin.permissions import OwnedMixin
from studyplatform.lib.asl import study_prompts
from studyplatform.models import PARTICIPANT_FACING_FIELDS, AslVideo, SignedTemplate


class AslVideoInline(GenericTabularInline):
    """Upload the ASL versions of an object's texts, one per text field."""

    model = AslVideo
    extra = 0
    fields = ("field_name", "video", "poster", "transcript", "credit")
    verbose_name = gettext_lazy("ASL video")
    verbose_name_plural = gettext_lazy("ASL videos of these texts")

    def get_formset(self, request, obj=None, **kwargs):
        model_name = self.parent_model._meta.model_name
        choices = [
            (name, self.parent_model._meta.get_field(name).verbose_name.capitalize())
            for name in PARTICIPANT_FACING_FIELDS[model_name]
        ]
        kwargs["form"] = type(
            "AslVideoForm",
            (forms.ModelForm,),
            {"field_name": forms.ChoiceField(choices=choices, label=gettext("Text"))},
        )
        return super().get_formset(request, obj, **kwargs)


class StudyAslMixin:
    """Add the study's "ASL videos" page: every text, whether it is signed, upload or record."""

    def asl_urls(self):
        return [
            path(
                "<path:object_id>/asl/",
                self.admin_site.admin_view(self.asl_view),
                name="studyplatform_study_asl",
            )
        ]

    def asl_view(self, request: HttpRequest, object_id: str) -> HttpResponse:
        """List the study's texts with their ASL videos; a POST attaches one (file or webcam)."""
        study = self._get_visible_study(request, object_id)
        if request.method == "POST":
            if not self.has_change_permission(request, study):
                raise PermissionDenied
            try:
                video = do_attach_asl_video(
                    study,
                    _posted_id(request.POST.get("content_type")),
                    _posted_id(request.POST.get("object_id")),
                    request.POST.get("field_name", ""),
                    request.FILES.get("video") or _missing_file(),
                )
            except (ValueError, ValidationError) as error:
                message = error.messages[0] if isinstance(error, ValidationError) else str(error)
                if request.headers.get("Accept") == "application/json":
                    return JsonResponse({"error": message}, status=400)
                messages.error(request, gettext("Not saved: %(problem)s") % {"problem": message})
            else:
                if request.headers.get("Accept") == "application/json":
                    return JsonResponse({"saved": True, "url": video.video.url})
                messages.success(request, gettext("ASL video saved."))
            return redirect(request.path)
        prompts = study_prompts(study)
        signed = sum(1 for prompt in prompts if prompt.video is not None)
        return self._page(
            request,
            "asl.html",
            gettext("ASL videos of “%(title)s”") % {"title": study.title},
            study=study,
            prompts=prompts,
            signed=signed,
        )


def _posted_id(value) -> int:
    """Return a posted row number, or ValidationError naming no Python internals."""
    text = str(value or "")
    if not (text.isascii() and text.isdigit() and len(text) <= 18):
        raise ValidationError(gettext("This text is not part of the study."))
    return int(text)


def _missing_file():
    raise ValidationError(gettext("Choose a video file or record one."))


@admin.register(SignedTemplate)
class SignedTemplateAdmin(OwnedMixin, admin.ModelAdmin):
    """A researcher's reusable signed texts; each sees and attaches only their own."""

    list_display = ("name", "kind", "study_count", "created_at")
    list_filter = ("kind",)
    fields = ("name", "kind", "video", "poster", "transcript")

    def get_queryset(self, request: HttpRequest):
        queryset = super().get_queryset(request).annotate(_studies=Count("studies"))
        return queryset if request.user.is_superuser else queryset.filter(owner=request.user)

    @admin.display(description=gettext_lazy("studies"), ordering="_studies")
    def study_count(self, template: SignedTemplate) -> int:
        return template._studies

    def save_model(self, request: HttpRequest, obj: SignedTemplate, form, change: bool) -> None:
        if not change:
            obj.owner = request.user
        super().save_model(request, obj, form, change)
