"""The SignStudy Django project: studies, participants, responses and the admin site.

The project package is also the platform's single Django app (label ``studyplatform``):
models live in :mod:`studyplatform.models`, multi-row writes in
:mod:`studyplatform.actions`, the researcher's UI in :mod:`studyplatform.admin`.
"""

from studyplatform.celery import app as celery_app

__all__ = ["celery_app"]
