"""Refuse what no view can use before any view or database sees it."""

import logging

from django.core.exceptions import BadRequest
from django.db import InterfaceError, OperationalError
from django.http import HttpRequest, JsonResponse

logger = logging.getLogger(__name__)

NUL = "\x00"


class RefuseNulMiddleware:
    """Answer 400 for a NUL character in the path, the query or a form; drop such cookies.

    PostgreSQL stores NUL in no text column, so ``/p/%00/`` (looked up as a token) or
    ``?a=%00`` (kept as a recruitment parameter) failed in the database with a server
    error (issue 33). No address, parameter or form of the platform holds one. A cookie
    with one is treated as absent (a session key is looked up too).
    """

    def __init__(self, get_response):
        self.get_response = get_response

    def __call__(self, request: HttpRequest):
        for name in [name for name, value in request.COOKIES.items() if NUL in name + value]:
            del request.COOKIES[name]
        if (
            NUL in request.path
            or _has_nul(request.GET)
            or (
                request.method == "POST"
                and request.content_type in FORMS
                and _has_nul(request.POST)
            )
        ):
            raise BadRequest("The request holds a NUL character.")
        return self.get_response(request)


FORMS = ("application/x-www-form-urlencoded", "multipart/form-data")


def _has_nul(query) -> bool:
    return any(NUL in key or any(NUL in value for value in values) for key, values in query.lists())


class DatabaseUnavailableMiddleware:
    """Answer 503 with Retry-After when the database cannot be reached, not 500.

    A restart of PostgreSQL (or SQLite's lock held past its timeout) is the server's
    trouble for a moment, not a fault in the request: the page's script retries a 5xx
    with backoff, and 503 says so to any other client and to monitoring.
    """

    RETRY_AFTER_S = 5

    def __init__(self, get_response):
        self.get_response = get_response

    def __call__(self, request: HttpRequest):
        return self.get_response(request)

    def process_exception(self, request: HttpRequest, exception: Exception):
        if not isinstance(exception, OperationalError | InterfaceError):
            return None
        logger.warning("database unavailable for %s: %s", request.path, exception)
        response = JsonResponse(
            {"error": "The server is busy for a moment; trying again."}, status=503
        )
        response["Retry-After"] = str(self.RETRY_AFTER_S)
        return response


class RefusedFormMiddleware:
    """Answer 400 to an admin form posted with errors, instead of 200.

    The admin shows the form again with its errors either way; the status tells a
    script, a proxy's log and the hostile-input harness that nothing was saved and why
    (issue 51: untrusted input gets a clear 4xx naming the problem). Forms without an
    error, and every GET, are untouched.
    """

    def __init__(self, get_response):
        self.get_response = get_response

    def __call__(self, request: HttpRequest):
        return self.get_response(request)

    def process_template_response(self, request: HttpRequest, response):
        errors = (getattr(response, "context_data", None) or {}).get("errors")
        if request.method == "POST" and response.status_code == 200 and errors:
            response.status_code = 400
        return response
