"""Send clips to be rendered: Celery jobs with a broker, else one background process.

Without a broker Celery runs jobs eagerly, inside the request that queued them, so a
researcher's browser would wait minutes for a study's clips. :func:`dispatch_renders`
starts ``manage.py render_stimuli`` in a process of its own instead, on the same
database and media folder, and returns at once; the progress page follows the clips.
"""

import os
import subprocess
import sys
from collections.abc import Sequence
from urllib.parse import quote

from django.conf import settings
from django.db import connection

from studyplatform.jobs.queue import RENDER_STIMULUS, queue_job

LOG_NAME = "render-background.log"


def _database_url() -> str:
    """Return the URL of the database this process uses (a test run's own included)."""
    db = connection.settings_dict
    if db["ENGINE"] == "django.db.backends.sqlite3":
        return f"sqlite:///{db['NAME']}"
    credentials = quote(db.get("USER") or "")
    if db.get("PASSWORD"):
        credentials += ":" + quote(db["PASSWORD"])
    host = db.get("HOST") or "localhost"
    port = f":{db['PORT']}" if db.get("PORT") else ""
    return f"postgres://{credentials}@{host}{port}/{quote(db['NAME'])}"


def start_render_process(stimulus_ids: Sequence[int]) -> subprocess.Popen:
    """Start a detached process that renders *stimulus_ids*; return it (not waited for)."""
    env = {
        **os.environ,
        "DJANGO_SETTINGS_MODULE": os.environ.get(
            "DJANGO_SETTINGS_MODULE", "studyplatform.settings"
        ),
        "DATABASE_URL": _database_url(),
        "SIGNSTUDY_MEDIA_ROOT": str(settings.MEDIA_ROOT),
    }
    log_dir = settings.VAR_DIR
    log_dir.mkdir(parents=True, exist_ok=True)
    with open(log_dir / LOG_NAME, "ab") as log:
        return subprocess.Popen(
            [sys.executable, "-m", "django", "render_stimuli", *map(str, stimulus_ids)],
            cwd=settings.BASE_DIR,
            env=env,
            stdin=subprocess.DEVNULL,
            stdout=log,
            stderr=subprocess.STDOUT,
            start_new_session=True,
        )


def dispatch_renders(stimulus_ids: Sequence[int], background: bool = False) -> str:
    """Render *stimulus_ids*: as Celery jobs, or in a background process where jobs would
    run eagerly and *background* is asked for. Return "queued" or "background"."""
    if background and settings.CELERY_TASK_ALWAYS_EAGER:
        start_render_process(stimulus_ids)
        return "background"
    for pk in stimulus_ids:
        queue_job(RENDER_STIMULUS, pk)
    return "queued"
