"""Celery jobs: render one stimulus clip.

A job is acknowledged only after it finished (``CELERY_TASK_ACKS_LATE``), and the clip
file is moved into place whole; a worker killed mid-render leaves the stimulus
"rendering", never "ready", and the broker hands the job to another worker.
"""

from pathlib import Path

from celery import shared_task
from django.conf import settings

from stimuli.clips import ClipSpec, render
from studyplatform.models import Stimulus

SUBDIRECTORY = "stimuli"


def render_now(stimulus_id: int) -> str:
    """Render one stimulus in this process; return its final status."""
    from studyplatform.actions.stimuli import (
        do_fail_stimulus,
        do_record_rendered_stimulus,
        do_start_rendering,
    )

    stimulus = Stimulus.objects.filter(pk=stimulus_id).first()
    if stimulus is None:
        return "missing"
    if stimulus.status == Stimulus.Status.READY and stimulus.video:
        return stimulus.status
    do_start_rendering(stimulus)
    try:
        spec = ClipSpec.from_dict(stimulus.parameters)
        clip = render(spec, Path(settings.MEDIA_ROOT) / SUBDIRECTORY)
    except Exception as error:  # any failure is recorded on the clip, for the admin
        return do_fail_stimulus(stimulus, error)
    return do_record_rendered_stimulus(stimulus, spec, clip, SUBDIRECTORY)


@shared_task(name="studyplatform.render_stimulus", acks_late=True, reject_on_worker_lost=True)
def render_stimulus(stimulus_id: int) -> str:
    """Render one stimulus (Celery job)."""
    return render_now(stimulus_id)
