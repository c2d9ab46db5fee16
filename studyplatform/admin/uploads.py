"""Add the study's "Uploaded clips" page: each item's clip in each uploaded condition,
uploaded one by one or as a zip with a manifest."""

from django.contrib import messages
from django.core.exceptions import PermissionDenied, ValidationError
from django.http import HttpRequest, HttpResponse, JsonResponse
from django.shortcuts import redirect
from django.urls import path
from django.utils.translation import gettext

from studyplatform.actions.clip_uploads import do_queue_clip, do_queue_clips_zip
from studyplatform.actions.clips import do_remove_uploaded_clip
from studyplatform.lib.uploads import mismatched_pairs, pending_uploads, uploads_overview
from studyplatform.models import ClipUpload, UploadedClip


class StudyUploadsMixin:
    """Add the study's Uploaded clips page."""

    def uploads_urls(self):
        return [
            path(
                "<path:object_id>/uploads/",
                self.admin_site.admin_view(self.uploads_view),
                name="studyplatform_study_uploads",
            ),
        ]

    def uploads_view(self, request: HttpRequest, object_id: str) -> HttpResponse:
        """List the items' uploaded clips; a POST uploads one, a zip of many, or removes one."""
        study = self._get_visible_study(request, object_id)
        if request.method == "POST":
            if not self.has_change_permission(request, study):
                raise PermissionDenied
            wants_json = request.headers.get("Accept") == "application/json"
            try:
                done = self._upload(request, study)
            except ValidationError as error:
                if wants_json:
                    return JsonResponse({"error": error.messages[0]}, status=400)
                messages.error(
                    request, gettext("Nothing saved: %(problem)s") % {"problem": error.messages[0]}
                )
            else:
                if wants_json:
                    return JsonResponse({"saved": done})
                messages.success(request, done)
            return redirect(request.path)
        conditions, rows = uploads_overview(study)
        return self._page(
            request,
            "uploads.html",
            gettext("Uploaded clips of “%(title)s”") % {"title": study.title},
            study=study,
            conditions=conditions,
            rows=rows,
            mismatched=mismatched_pairs(study),
            pending=pending_uploads(study),
            can_change=self.has_change_permission(request, study) and not study.design_locked,
        )

    def _upload(self, request: HttpRequest, study) -> str:
        """Carry out the page's POST; return what was done (ValidationError if nothing)."""
        if "remove" in request.POST:
            clip = UploadedClip.objects.filter(
                pk=_number(request.POST["remove"]), condition__study=study
            ).first()
            if clip is None:
                raise ValidationError(gettext("No such clip in this study."))
            do_remove_uploaded_clip(clip)
            return gettext("Clip of %(item)s in %(condition)s removed.") % {
                "item": clip.item.key,
                "condition": clip.condition.key,
            }
        if "archive" in request.FILES:
            return self._outcome(do_queue_clips_zip(study, request.FILES["archive"]))
        condition = study.conditions.filter(pk=_number(request.POST.get("condition"))).first()
        item = study.items.filter(pk=_number(request.POST.get("item"))).first()
        if condition is None or item is None:
            raise ValidationError(gettext("That condition or item is not part of the study."))
        upload = request.FILES.get("clip")
        if upload is None:
            raise ValidationError(gettext("Choose a video file (MP4, WebM or MOV)."))
        return self._outcome(do_queue_clip(condition, item, upload))

    @staticmethod
    def _outcome(job: ClipUpload) -> str:
        """Return what became of a queued upload: its message once converted (at once
        where jobs run in this process), else that it is converting."""
        job.refresh_from_db()
        if job.status == ClipUpload.Status.FAILED:
            raise ValidationError(job.message)
        if job.status == ClipUpload.Status.DONE:
            return job.message
        return gettext(
            "%(name)s is being converted in the background; this page lists it until it is saved."
        ) % {"name": job.original_name}


def _number(value) -> int:
    try:
        return int(value)
    except (TypeError, ValueError):
        return 0
