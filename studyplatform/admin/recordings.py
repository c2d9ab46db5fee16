"""Add the study's "Recordings" page: each word's recording, upload or record one, and
follow its capture."""

from django.contrib import messages
from django.core.exceptions import PermissionDenied, ValidationError
from django.http import HttpRequest, HttpResponse, JsonResponse
from django.shortcuts import redirect
from django.urls import path
from django.utils.translation import gettext

from studyplatform.actions.recordings import do_attach_recording
from studyplatform.lib.recordings import recordings_overview


class StudyRecordingsMixin:
    """Add the study's Recordings page and its progress poll."""

    def recordings_urls(self):
        return [
            path(
                "<path:object_id>/recordings/",
                self.admin_site.admin_view(self.recordings_view),
                name="studyplatform_study_recordings",
            ),
            path(
                "<path:object_id>/recordings/progress.json",
                self.admin_site.admin_view(self.recordings_progress_view),
                name="studyplatform_study_recordings_progress",
            ),
        ]

    def recordings_view(self, request: HttpRequest, object_id: str) -> HttpResponse:
        """List the study's words with their recordings; a POST attaches one to a word."""
        study = self._get_visible_study(request, object_id)
        if request.method == "POST":
            if not self.has_change_permission(request, study):
                raise PermissionDenied
            wants_json = request.headers.get("Accept") == "application/json"
            try:
                item = study.items.filter(pk=_number(request.POST.get("item"))).first()
                if item is None:
                    raise ValidationError(gettext("This word is not part of the study."))
                upload = request.FILES.get("recording")
                if upload is None:
                    raise ValidationError(
                        gettext("Choose a video, .pose or BVH file, or record one.")
                    )
                do_attach_recording(
                    item,
                    upload,
                    mirrored="mirrored" in request.POST,
                    one_hand="one_hand" in request.POST,
                )
            except ValidationError as error:
                if wants_json:
                    return JsonResponse({"error": error.messages[0]}, status=400)
                messages.error(
                    request, gettext("Not saved: %(problem)s") % {"problem": error.messages[0]}
                )
            else:
                if wants_json:
                    return JsonResponse({"saved": True})
                messages.success(
                    request,
                    gettext("Recording of %(key)s saved; it is being prepared.")
                    % {"key": item.key},
                )
            return redirect(request.path)
        return self._page(
            request,
            "recordings.html",
            gettext("Recordings of “%(title)s”") % {"title": study.title},
            study=study,
            overview=recordings_overview(study),
        )

    def recordings_progress_view(self, request: HttpRequest, object_id: str) -> JsonResponse:
        """Return the recordings' capture progress as JSON, for the page to poll."""
        return JsonResponse(recordings_overview(self._get_visible_study(request, object_id)))


def _number(value) -> int:
    try:
        return int(value)
    except (TypeError, ValueError):
        return 0
