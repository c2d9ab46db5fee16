"""List the rendered clips of each study, with their parameters and a player."""

from django.contrib import admin
from django.utils.html import format_html

from studyplatform.actions.stimuli import do_retry_stimuli
from studyplatform.admin.design import OwnStudyFilter
from studyplatform.admin.permissions import StudyScopedMixin
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
        "player", "condition", "item", "status", "error", "content_hash", "parameters",
        "engine_version", "duration_ms", "frame_count", "width", "height", "size_bytes",
        "sha256", "video", "poster", "created_at", "rendered_at",
    )  # fmt: skip
    actions = ("retry_stimuli",)

    def has_add_permission(self, request) -> bool:
        return False

    @admin.action(description="Retry the selected clips (those not rendered)")
    def retry_stimuli(self, request, queryset) -> None:
        count = do_retry_stimuli(queryset, background=True)
        self.message_user(request, f"{count} clip(s) queued again.")

    @admin.display(description="clip")
    def player(self, stimulus: Stimulus) -> str:
        if not stimulus.video_url:
            return "Not uploaded yet." if stimulus.condition.is_uploaded else "Not rendered yet."
        return format_html(
            '<video src="{}" poster="{}" controls preload="metadata" width="480"></video>',
            stimulus.video_url,
            stimulus.poster_url,
        )
