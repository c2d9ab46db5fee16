"""Expose the WSGI callable of the SignStudy platform as ``application``."""

import os

from django.core.wsgi import get_wsgi_application

os.environ.setdefault("DJANGO_SETTINGS_MODULE", "studyplatform.settings")

application = get_wsgi_application()
