"""Answer a participant in their study's language (issue 55).

A participant's pages, the messages their saves answer and the JavaScript catalogue are
in ``Study.language``, or in the participant's browser language where the study follows
it and the interface has that language; a link that names no study is answered in the
browser's language where the interface has it, else in English. The researcher's pages stay in
``settings.LANGUAGE_CODE``: no LocaleMiddleware, so a browser's language never changes a
page its study did not allow it to.
"""

from functools import wraps

from django.conf import settings
from django.http import Http404, HttpRequest, HttpResponse
from django.utils import translation
from django.utils.translation.trans_real import parse_accept_lang_header
from django.views.decorators.cache import cache_page
from django.views.i18n import JavaScriptCatalog

from studyplatform.models import Study


def browser_language(request: HttpRequest) -> str | None:
    """Return the interface language the browser prefers (Accept-Language), or None."""
    # Django's own parser (what LocaleMiddleware uses): bounded, checked, by preference.
    header = request.headers.get("Accept-Language", "")
    for code, _ in parse_accept_lang_header(header):
        if code != "*":
            try:
                return translation.get_supported_language_variant(code)
            except LookupError:
                continue
    return None


def study_language(request: HttpRequest, study: Study | None) -> str:
    """Return the language *study*'s pages are shown in to the browser of *request*."""
    if study is None:
        return browser_language(request) or settings.LANGUAGE_CODE
    if study.follow_browser_language:
        return browser_language(request) or study.language
    return study.language


def speak(request: HttpRequest, study: Study) -> None:
    """Answer the rest of *request* in *study*'s language (inside :func:`in_study_language`).

    The view calls it once it has the study it loaded anyway, so the language costs no
    query of its own; what it says before (an unknown link) is in the browser's language.
    """
    language = study_language(request, study)
    translation.activate(language)
    request.LANGUAGE_CODE = language


def in_study_language(view):
    """Run a participant view in the browser's interface language until it calls
    :func:`speak`, restore the language after it, and say which it was (Content-Language)."""

    @wraps(view)
    def wrapped(request: HttpRequest, *args, **kwargs) -> HttpResponse:
        language = study_language(request, None)
        with translation.override(language):
            request.LANGUAGE_CODE = language
            response = view(request, *args, **kwargs)
            response.headers.setdefault("Content-Language", translation.get_language())
        return response

    return wrapped


_CATALOGUE = JavaScriptCatalog.as_view(packages=["studyplatform"])


# The same for every request in a language (until a deployment restarts the server):
# cached, as Django's documentation advises, instead of read from the catalogues on each
# participant page; browsers keep it for the hour too.
@cache_page(3600)
def javascript_catalog(request: HttpRequest, language: str) -> HttpResponse:
    """Serve participate.js's translations in *language* (Django's JavaScript catalogue)."""
    if language not in dict(settings.LANGUAGES):
        raise Http404("No such language.")
    with translation.override(language):
        return _CATALOGUE(request)
