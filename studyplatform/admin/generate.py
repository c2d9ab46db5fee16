"""Generate a study's stimuli from the admin and follow their rendering."""

from django.contrib import admin, messages
from django.http import HttpRequest, HttpResponse, JsonResponse
from django.shortcuts import redirect
from django.urls import path, reverse
from django.utils.html import format_html
from django.utils.translation import gettext, gettext_lazy

from stimuli.clips import ClipError
from stimuli.manifest import manifest_dict
from studyplatform.actions.stimuli import GenerateOptions, IdenticalClips, do_generate_stimuli
from studyplatform.lib.stimuli import (
    clips_on_disk,
    group_identical,
    hashed_pairs,
    needed_pairs,
    stimuli_progress,
    study_manifest,
    uploaded_manifest,
)
from studyplatform.lib.stimulus_checks import stored_checks
from studyplatform.models import Study


class StudyGenerateMixin:
    """Add the generate, progress and manifest pages and the list's generate action."""

    def generate_urls(self):
        view = self.admin_site.admin_view
        return [
            path(
                "<path:object_id>/stimuli/generate/",
                view(self.generate_view),
                name="studyplatform_study_generate",
            ),
            path(
                "<path:object_id>/stimuli/",
                view(self.stimuli_view),
                name="studyplatform_study_stimuli",
            ),
            path(
                "<path:object_id>/stimuli/progress.json",
                view(self.stimuli_progress_view),
                name="studyplatform_study_stimuli_progress",
            ),
            path(
                "<path:object_id>/stimuli/manifest.json",
                view(self.stimuli_manifest_view),
                name="studyplatform_study_stimuli_manifest",
            ),
        ]

    def _generate(self, request: HttpRequest, study: Study, allow_identical: bool):
        """Generate *study*'s clips in the background; return the result or the refusal."""
        try:
            return do_generate_stimuli(
                study,
                GenerateOptions(
                    background=True, allow_identical=allow_identical or study.allow_identical_clips
                ),
            ), None
        except IdenticalClips as refusal:
            return None, refusal
        except ClipError as error:
            messages.error(request, f"“{study.title}”: {error}")  # the engine says what
            return None, None

    def generate_view(self, request: HttpRequest, object_id: str) -> HttpResponse:
        """Ask to generate the study's clips (naming identical ones); start it on POST."""
        study = self._get_visible_study(request, object_id)
        allowed = self.has_change_permission(request, study)
        if request.method == "POST" and allowed:
            confirmed = request.POST.get("allow_identical") == "1"
            result, refusal = self._generate(request, study, confirmed)
            if result is not None:
                messages.success(request, _generated(result), extra_tags="generation-started")
                return redirect(reverse("admin:studyplatform_study_stimuli", args=[study.pk]))
            if refusal is None:
                return redirect(reverse("admin:studyplatform_study_generate", args=[study.pk]))
        title = gettext("Generate the stimuli of “%(title)s”") % {"title": study.title}
        pairs = needed_pairs(study)
        hashed = hashed_pairs(pairs)  # the page's two counts share the hashing
        return self._page(
            request,
            "generate.html",
            title,
            study=study,
            allowed=allowed,
            identical=group_identical(hashed),
            clips=len(pairs),
            progress=stimuli_progress(study),
            checks=stored_checks(hashed),
            on_disk=clips_on_disk(hashed),
        )

    def stimuli_view(self, request: HttpRequest, object_id: str) -> HttpResponse:
        """Show the study's clips being rendered: a live progress bar, the failures and
        the stimulus check's warnings."""
        study = self._get_visible_study(request, object_id)
        checks = stored_checks(hashed_pairs(needed_pairs(study)))
        return self._page(
            request,
            "stimuli.html",
            gettext("Stimuli of “%(title)s”") % {"title": study.title},
            study=study,
            progress=stimuli_progress(study),
            checks=checks,
        )

    def stimuli_progress_view(self, request: HttpRequest, object_id: str) -> JsonResponse:
        """Return the rendering progress as JSON, for the progress bar to poll."""
        return JsonResponse(stimuli_progress(self._get_visible_study(request, object_id)))

    def stimuli_manifest_view(self, request: HttpRequest, object_id: str) -> JsonResponse:
        """Download the study's stimulus manifest (every clip's spec, facts and checksum)."""
        study = self._get_visible_study(request, object_id)
        manifest = manifest_dict(study_manifest(study), study.slug, uploaded_manifest(study))
        response = JsonResponse(manifest, json_dumps_params={"indent": 1, "ensure_ascii": False})
        response["Content-Disposition"] = f'attachment; filename="{study.slug}-stimuli.json"'
        return response

    @admin.action(description=gettext_lazy("Generate stimuli (render missing clips)"))
    def generate_stimuli(self, request: HttpRequest, queryset):
        """Start generating the selected studies' clips; one study opens its progress page."""
        studies, started = list(queryset), []
        for study in studies:
            if not self.has_change_permission(request, study):
                messages.error(
                    request, gettext("You cannot change “%(title)s”.") % {"title": study.title}
                )
                continue
            result, refusal = self._generate(request, study, allow_identical=False)
            if refusal is not None:
                messages.error(
                    request,
                    format_html(
                        "“{}”: {} <a href='{}'>{}</a>.",
                        study.title,
                        str(refusal),
                        reverse("admin:studyplatform_study_generate", args=[study.pk]),
                        gettext("Review and confirm"),
                    ),
                )
            if result is None:
                continue
            started.append(study)
            messages.success(
                request,
                format_html(
                    "“{}”: {} <a href='{}'>{}</a>",
                    study.title,
                    _generated(result),
                    reverse("admin:studyplatform_study_stimuli", args=[study.pk]),
                    gettext("Progress"),
                ),
                extra_tags="generation-started",
            )
        if len(studies) == 1 and started:
            return redirect(reverse("admin:studyplatform_study_stimuli", args=[started[0].pk]))
        return None


def _generated(result) -> str:
    """Say what generation did: clips queued, ready, and uploads still missing."""
    text = gettext("%(total)d clips: %(queued)d being rendered, %(ready)d ready.") % {
        "total": result.total,
        "queued": result.queued,
        "ready": result.ready,
    }
    if result.missing:
        text += " " + gettext(
            "%(missing)d of the uploaded conditions' clips are not uploaded yet "
            "(Uploaded clips page)."
        ) % {"missing": result.missing}
    return text
