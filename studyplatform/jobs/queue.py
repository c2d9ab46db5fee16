"""Queue the platform's background jobs by their registered names, once the write commits.

Actions queue jobs here instead of importing the job functions (Zulip's
``queue_event_on_commit``), so that the jobs in :mod:`studyplatform.tasks` may call the
actions without an import circle. A worker finds the jobs by name; with no broker
(``CELERY_TASK_ALWAYS_EAGER``) a job runs in this process, as ``delay()`` would:
``send_task`` ignores eager mode and would leave it on the in-memory broker, never run.
"""

from django.conf import settings
from django.db import transaction

RENDER_STIMULUS = "studyplatform.render_stimulus"
PREPARE_RECORDING = "studyplatform.prepare_recording"
PREPARE_AVATAR = "studyplatform.prepare_avatar"
PREPARE_CLIPS = "studyplatform.prepare_clips"
CLEAN_ABANDONED_UPLOADS = "studyplatform.clean_abandoned_uploads"
APPLY_RETENTION = "studyplatform.apply_retention"


def queue_job(name: str, *args) -> object:
    """Send the job registered as *name* with *args* to a worker, or run it here when
    jobs run eagerly; return Celery's result."""
    from studyplatform.celery import app

    if not settings.CELERY_TASK_ALWAYS_EAGER:
        return app.send_task(name, args=args)
    if name not in app.tasks:
        app.loader.import_default_modules()  # the jobs a worker finds when it starts
    return app.tasks[name].apply(args=args)


def queue_job_on_commit(name: str, *args) -> None:
    """Queue the job *name* with *args* once the current transaction commits (at once
    outside one); a rolled-back write queues nothing."""
    transaction.on_commit(lambda: queue_job(name, *args))
