"""Create the Celery application that runs the platform's background jobs.

The broker comes from ``CELERY_BROKER_URL`` (or ``REDIS_URL``) in the settings; with no
broker configured, tasks run eagerly in the calling process. Start a worker with
``celery -A studyplatform.celery worker``.
"""

import os

from celery import Celery

os.environ.setdefault("DJANGO_SETTINGS_MODULE", "studyplatform.settings")

app = Celery("studyplatform")
app.config_from_object("django.conf:settings", namespace="CELERY")
app.autodiscover_tasks()
