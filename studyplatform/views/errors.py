"""Answer requests Django refuses before a view runs: JSON for the page's script.

A body over ``DATA_UPLOAD_MAX_MEMORY_SIZE``, a path no URL matches or a refused CSRF
token used to get Django's HTML error page, which the participant page's script cannot
show; a request that asked for JSON (or sent JSON or a recording) now gets
``{"error": …}`` with the same status.
"""

from django.core.exceptions import RequestDataTooBig
from django.http import HttpRequest, HttpResponse, JsonResponse
from django.views import defaults

JSON_BODIES = ("application/json", "application/octet-stream", "video/webm", "video/mp4")


def _wants_json(request: HttpRequest) -> bool:
    accept = request.headers.get("Accept", "")
    return "application/json" in accept or request.content_type in JSON_BODIES


def _json(message: str, status: int) -> JsonResponse:
    return JsonResponse({"error": message}, status=status)


def bad_request(request: HttpRequest, exception: Exception) -> HttpResponse:
    """Answer 400, or 413 for a body over the upload limit."""
    if isinstance(exception, RequestDataTooBig):
        if _wants_json(request):
            return _json("The request is larger than the server takes.", 413)
        return HttpResponse(
            "The request is larger than the server takes.",
            status=413,
            content_type="text/plain; charset=utf-8",
        )
    if _wants_json(request):
        return _json("The request could not be read.", 400)
    return defaults.bad_request(request, exception)


def permission_denied(request: HttpRequest, exception: Exception) -> HttpResponse:
    """Answer 403."""
    if _wants_json(request):
        return _json("This request is not allowed.", 403)
    return defaults.permission_denied(request, exception)


def page_not_found(request: HttpRequest, exception: Exception) -> HttpResponse:
    """Answer 404."""
    if _wants_json(request):
        return _json("There is nothing at this address.", 404)
    return defaults.page_not_found(request, exception)


def server_error(request: HttpRequest) -> HttpResponse:
    """Answer 500."""
    if _wants_json(request):
        return _json("The server could not answer; please try again.", 500)
    return defaults.server_error(request)


def csrf_failure(request: HttpRequest, reason: str = "") -> HttpResponse:
    """Answer a refused CSRF check (403) with a message the page can show."""
    if _wants_json(request):
        return _json("This page has expired; please reload it.", 403)
    from django.views.csrf import csrf_failure as django_csrf_failure

    return django_csrf_failure(request, reason)
