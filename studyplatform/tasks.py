"""Celery jobs: render one stimulus clip.

A job is acknowledged only after it finished (``CELERY_TASK_ACKS_LATE``), and the clip
file is moved into place whole; a worker killed mid-render leaves the stimulus
"rendering", never "ready", and the broker hands the job to another worker.
"""

from pathlib import Path

from celery import shared_task
from django.conf import settings
from django.db import transaction
from django.utils import timezone

from stimuli.clips import ClipSpec, render
from studyplatform.models import Stimulus

SUBDIRECTORY = "stimuli"


def render_now(stimulus_id: int) -> str:
    """Render one stimulus in this process; return its final status."""
    stimulus = Stimulus.objects.filter(pk=stimulus_id).first()
    if stimulus is None:
        return "missing"
    if stimulus.status == Stimulus.Status.READY and stimulus.video:
        return stimulus.status
    Stimulus.objects.filter(pk=stimulus_id).update(status=Stimulus.Status.RENDERING)
    try:
        spec = ClipSpec.from_dict(stimulus.parameters)
        clip = render(spec, Path(settings.MEDIA_ROOT) / SUBDIRECTORY)
    except Exception as error:  # any failure is recorded on the clip, for the admin
        Stimulus.objects.filter(pk=stimulus_id).update(
            status=Stimulus.Status.FAILED, error=f"{type(error).__name__}: {error}"
        )
        return Stimulus.Status.FAILED
    with transaction.atomic():
        stimulus = Stimulus.objects.select_for_update().get(pk=stimulus_id)
        if stimulus.content_hash != spec.content_hash():
            return "superseded"  # the study changed while this clip rendered
        stimulus.video.name = f"{SUBDIRECTORY}/{clip.video.name}"
        stimulus.poster.name = f"{SUBDIRECTORY}/{clip.poster.name}"
        stimulus.duration_ms = clip.duration_ms
        stimulus.frame_count = clip.frame_count
        stimulus.width, stimulus.height = clip.width, clip.height
        stimulus.size_bytes = clip.size_bytes
        stimulus.sha256 = clip.sha256
        stimulus.status = Stimulus.Status.READY
        stimulus.error = ""
        stimulus.rendered_at = timezone.now()
        stimulus.save()
    return stimulus.status


@shared_task(name="studyplatform.render_stimulus", acks_late=True, reject_on_worker_lost=True)
def render_stimulus(stimulus_id: int) -> str:
    """Render one stimulus (Celery job)."""
    return render_now(stimulus_id)
