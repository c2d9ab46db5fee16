"""List the clips of each study, with their parameters, a player and their motion."""

from django.contrib import admin
from django.http import Http404, HttpRequest, HttpResponse
from django.urls import path, reverse
from django.utils.html import format_html
from django.utils.translation import gettext, gettext_lazy, ngettext

from studyplatform.actions.stimuli import do_retry_stimuli
from studyplatform.admin.design import OwnStudyFilter
from studyplatform.admin.permissions import StudyScopedMixin
from studyplatform.lib.motion import FORMATS, NoMotion, stimulus_motion
from studyplatform.models import Stimulus


@admin.register(Stimulus)
class StimulusAdmin(StudyScopedMixin, admin.ModelAdmin):
    study_path = "condition__study"
    list_display = (
        "item",
        "condition",
        "status",
        "duration_ms",
        "frame_count",
        "engine_version",
        "rendered_at",
    )
    list_filter = (("condition__study", OwnStudyFilter), "status", "condition__is_simulated")
    search_fields = ("item__key", "condition__key", "content_hash")
    list_select_related = ("item", "condition")
    # A clip's record is its provenance: what rendered it, from what, with which result.
    # Nobody edits it; generation writes it and "Retry" re-renders it.
    fields = readonly_fields = (
        "player",
        "motion",
        "condition",
        "item",
        "status",
        "error",
        "content_hash",
        "parameters",
        "engine_version",
        "duration_ms",
        "frame_count",
        "width",
        "height",
        "size_bytes",
        "sha256",
        "video",
        "poster",
        "created_at",
        "rendered_at",
    )
    actions = ("retry_stimuli",)

    def has_add_permission(self, request) -> bool:
        return False

    @admin.action(description=gettext_lazy("Retry the selected clips (those not rendered)"))
    def retry_stimuli(self, request, queryset) -> None:
        count = do_retry_stimuli(queryset, background=True)
        self.message_user(
            request,
            ngettext("%(count)d clip queued again.", "%(count)d clips queued again.", count)
            % {"count": count},
        )

    @admin.display(description=gettext_lazy("clip"))
    def player(self, stimulus: Stimulus) -> str:
        if not stimulus.video_url:
            return (
                gettext("Not uploaded yet.")
                if stimulus.condition.is_uploaded
                else gettext("Not rendered yet.")
            )
        return format_html(
            '<video src="{}" poster="{}" controls preload="metadata" width="480"></video>',
            stimulus.video_url,
            stimulus.poster_url,
        )

    @admin.display(description=gettext_lazy("motion"))
    def motion(self, stimulus: Stimulus) -> str:
        """Offer the clip's motion as GLB (avatar, face and camera too) and BVH."""
        if stimulus.pk is None or stimulus.condition.is_uploaded:
            return gettext("An uploaded video: no motion.")
        links = [
            format_html(
                '<a href="{}" download>{}</a>',
                reverse("admin:studyplatform_stimulus_motion", args=[stimulus.pk, fmt]),
                label,
            )
            for fmt, label in (
                ("glb", gettext("GLB: avatar, motion, face and camera")),
                ("bvh", "BVH"),
            )
        ]
        return format_html(
            '{} · {}<div class="help">{}</div>',
            *links,
            gettext(
                "Open exactly what participants saw in Blender, Unity or three.js (GLB), or "
                "the joints' motion in any BVH tool; made again from the clip's parameters "
                "by this installation's engine."
            ),
        )

    def get_urls(self):
        view = self.admin_site.admin_view(self.motion_view)
        own = [
            path("<path:object_id>/motion.<str:fmt>", view, name="studyplatform_stimulus_motion")
        ]
        return own + super().get_urls()

    def motion_view(self, request: HttpRequest, object_id: str, fmt: str) -> HttpResponse:
        """Download the clip's motion as *fmt* (glb or bvh)."""
        stimulus = self.get_object(request, object_id)
        if (
            stimulus is None
            or not self.has_view_permission(request, stimulus)
            or fmt not in FORMATS
        ):
            raise Http404("No such clip.")
        try:
            data, name = stimulus_motion(stimulus, fmt)
        except (NoMotion, ValueError) as error:
            return HttpResponse(str(error), status=409, content_type="text/plain; charset=utf-8")
        response = HttpResponse(data, content_type=FORMATS[fmt])
        response["Content-Disposition"] = f'attachment; filename="{name}"'
        return response
