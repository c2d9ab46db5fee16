"""Expose the ASGI callable of the SignStudy platform as ``application``."""

import os

from django.core.asgi import get_asgi_application

os.environ.setdefault("DJANGO_SETTINGS_MODULE", "studyplatform.settings")

application = get_asgi_application()
