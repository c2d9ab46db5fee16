"""Serve rendered clips and uploaded videos when no web server does (the demo, tests)."""

from django.conf import settings
from django.http import HttpRequest, HttpResponse
from django.views.static import serve


def media(request: HttpRequest, path: str) -> HttpResponse:
    """Send the file at *path* under MEDIA_ROOT, read at request time (it can change)."""
    return serve(request, path, document_root=settings.MEDIA_ROOT)
