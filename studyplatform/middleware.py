"""Refuse what no view can use before any view or database sees it."""

from django.core.exceptions import BadRequest
from django.http import HttpRequest

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
        if NUL in request.path or _has_nul(request.GET) or (
            request.method == "POST" and request.content_type in FORMS and _has_nul(request.POST)
        ):  # fmt: skip
            raise BadRequest("The request holds a NUL character.")
        return self.get_response(request)


FORMS = ("application/x-www-form-urlencoded", "multipart/form-data")


def _has_nul(query) -> bool:
    return any(NUL in key or any(NUL in value for value in values)
               for key, values in query.lists())  # fmt: skip
