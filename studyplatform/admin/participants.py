"""Let researchers read who took part and what they answered (read-only)."""

import re

from django.contrib import admin
from django.http import HttpRequest
from django.utils.translation import gettext_lazy

from studyplatform.actions import do_withdraw_participant
from studyplatform.admin.design import OwnStudyFilter
from studyplatform.admin.permissions import StudyScopedMixin
from studyplatform.models import MediaEvent, Participant, PersonalAnswer, Response, Withdrawal

WITHDRAWN_IN_ADMIN = "deleted in the admin (withdrawal)"


class ReadOnlyMixin:
    """Show data collected from participants without letting anyone alter it."""

    def has_add_permission(self, request: HttpRequest, obj=None) -> bool:
        return False

    def has_change_permission(self, request: HttpRequest, obj=None) -> bool:
        return False


class ResponseInline(ReadOnlyMixin, admin.TabularInline):
    model = Response
    extra = 0
    fields = ("trial", "question", "chosen", "chosen_position", "rating", "text", "video", "rt_ms")
    readonly_fields = fields
    can_delete = False


PARTICIPANT_LINK = re.compile(r"/p/([^/?#\s]+)")


@admin.register(Participant)
class ParticipantAdmin(StudyScopedMixin, ReadOnlyMixin, admin.ModelAdmin):
    list_display = (
        "pk",
        "study",
        "started_at",
        "finished_at",
        "is_pilot",
        "language",
        "position",
    )
    list_filter = (("study", OwnStudyFilter), "is_pilot", "language", "finished_at")
    # A participant who writes in is found by their link, completion code or the
    # recruitment service's id (PROLIFIC_PID, in the parameters they arrived with).
    search_fields = ("=token", "=completion_code", "recruitment_params")
    search_help_text = gettext_lazy(
        "A participant's link (or its token), completion code or Prolific id."
    )
    date_hierarchy = "started_at"
    readonly_fields = (
        "study",
        "token",
        "recruitment_params",
        "seed",
        "schedule",
        "language",
        "is_pilot",
        "position",
        "reached",
        "user_agent",
        "started_at",
        "consented_at",
        "last_seen_at",
        "finished_at",
    )
    inlines = (ResponseInline,)

    def get_search_results(self, request: HttpRequest, queryset, search_term: str):
        # A pasted link /p/<token>/ is searched as its token.
        found = PARTICIPANT_LINK.search(search_term)
        term = found.group(1) if found else search_term
        return super().get_search_results(request, queryset, term)

    # Deleting a participant is a withdrawal: their signed-answer videos go too, and the
    # Withdrawals list records it (Django's own delete would leave the files behind).
    def delete_model(self, request: HttpRequest, obj: Participant) -> None:
        do_withdraw_participant(obj, by=request.user, reason=WITHDRAWN_IN_ADMIN)

    def get_deleted_objects(self, objs, request: HttpRequest):
        # A withdrawal takes the participant's answers and events with it by design: the
        # researcher needs no delete permission on those (they have none, to edit data).
        deleted, counts, _, protected = super().get_deleted_objects(objs, request)
        return deleted, counts, set(), protected

    def delete_queryset(self, request: HttpRequest, queryset) -> None:
        for participant in queryset:
            do_withdraw_participant(participant, by=request.user, reason=WITHDRAWN_IN_ADMIN)


@admin.register(Withdrawal)
class WithdrawalAdmin(StudyScopedMixin, ReadOnlyMixin, admin.ModelAdmin):
    list_display = (
        "participant_number",
        "study",
        "withdrawn_at",
        "withdrawn_by",
        "responses",
        "events",
        "personal_answers",
        "files",
    )
    list_filter = (("study", OwnStudyFilter),)
    readonly_fields = (*list_display, "reason")

    def has_delete_permission(self, request: HttpRequest, obj=None) -> bool:
        return False  # the audit trail stays


@admin.register(PersonalAnswer)
class PersonalAnswerAdmin(StudyScopedMixin, ReadOnlyMixin, admin.ModelAdmin):
    study_path = "participant__study"
    list_display = ("participant", "question", "value")
    readonly_fields = ("participant", "question", "value")


@admin.register(Response)
class ResponseAdmin(StudyScopedMixin, ReadOnlyMixin, admin.ModelAdmin):
    study_path = "participant__study"
    list_display = (
        "participant",
        "trial",
        "question",
        "chosen",
        "chosen_position",
        "rating",
        "rt_ms",
        "revision",
        "answered_at",
    )
    list_filter = (
        ("participant__study", OwnStudyFilter),
        "question__kind",
        "participant__is_pilot",
    )
    search_fields = ("trial__key", "question__key", "text")
    list_select_related = ("participant", "trial", "question")
    readonly_fields = (
        "participant",
        "trial",
        "question",
        "chosen",
        "chosen_position",
        "rating",
        "number",
        "text",
        "video",
        "score",
        "rt_ms",
        "answered_client_ms",
        "revision",
        "answered_at",
        "updated_at",
    )


@admin.register(MediaEvent)
class MediaEventAdmin(StudyScopedMixin, ReadOnlyMixin, admin.ModelAdmin):
    study_path = "participant__study"
    list_display = ("participant", "trial", "clip_position", "kind", "media_time_s", "created_at")
    list_filter = (("participant__study", OwnStudyFilter), "kind")
    list_select_related = ("participant", "trial")
    readonly_fields = (
        "participant",
        "trial",
        "stimulus",
        "clip_position",
        "kind",
        "media_time_s",
        "client_time_ms",
        "detail",
        "created_at",
    )
