"""Serve media: public clips and prompts, and personal files only to those allowed.

Stimulus clips are named by their content hash, so browsers may keep them for a year;
ASL prompts can be replaced under the same name, so they are revalidated daily.
Signed answers and signers' recordings are private (:mod:`studyplatform.files.storage`): the
study's researchers may open them in the admin, and a participant may play back their
own answer while taking part. Everyone else gets 404, as if the file did not exist.

Every file is served with the fixed type of its extension (studyplatform.files.media_types),
``nosniff`` and a sandboxing policy; a motion file is a download. A file of any other
extension is not served at all, whoever put it there.
"""

from pathlib import Path

from django.conf import settings
from django.core.exceptions import SuspiciousFileOperation
from django.db.models import Q
from django.http import Http404, HttpRequest, HttpResponse
from django.utils._os import safe_join
from django.views.decorators.http import require_safe

from studyplatform.admin.permissions import owned_studies
from studyplatform.files.media_types import MEDIA_CSP, SERVED
from studyplatform.files.storage import PRIVATE_STORAGE
from studyplatform.lib import exchange
from studyplatform.models import Avatar, Recording, Response, Study, UploadedClip
from studyplatform.views.files import file_response

PUBLIC_CACHE = {"stimuli": "public, max-age=31536000, immutable"}
PUBLIC_CACHE_DEFAULT = "public, max-age=86400"
PRIVATE_CACHE = "private, no-store"
# An uploaded clip is named by its content, but may stop being served when its study
# closes: browsers keep it for a day, and no shared cache keeps it.
UPLOADED_CACHE = "private, max-age=86400"


def _existing_file(root, name: str) -> Path:
    try:
        path = Path(safe_join(root, name))
    except SuspiciousFileOperation:  # a path that leaves the root
        raise Http404("No such file.") from None
    if path.suffix.lower() not in SERVED or not path.is_file():
        raise Http404("No such file.")
    return path


def _as_media(response: HttpResponse, path: Path) -> HttpResponse:
    """Give *response* the headers every media file is served with (its fixed type too)."""
    kind = SERVED[path.suffix.lower()]
    response["Content-Type"] = kind.content_type
    response["Content-Security-Policy"] = MEDIA_CSP
    response["X-Content-Type-Options"] = "nosniff"
    if not kind.inline:
        response["Content-Disposition"] = f'attachment; filename="{path.name}"'
    return response


@require_safe
def media(request: HttpRequest, path: str) -> HttpResponse:
    """Send the public media file at *path* (read at request time: it can change)."""
    found = _existing_file(settings.MEDIA_ROOT, path)
    cache = PUBLIC_CACHE.get(path.split("/", 1)[0], PUBLIC_CACHE_DEFAULT)
    return _as_media(file_response(request, found, cache_control=cache), found)


def _private_file(request: HttpRequest, name: str, cache: str = PRIVATE_CACHE) -> HttpResponse:
    path = _existing_file(PRIVATE_STORAGE.location, name)
    header = settings.SIGNSTUDY_SENDFILE_HEADER
    if not header:
        return _as_media(file_response(request, path, cache_control=cache), path)
    response = HttpResponse()  # the web server sends the body, its length and ranges
    if header.lower() == "x-accel-redirect":
        response[header] = settings.SIGNSTUDY_SENDFILE_PREFIX.rstrip("/") + "/" + name
    else:
        response[header] = str(path)
    response["Cache-Control"] = cache
    return _as_media(response, path)


def _may_open(request: HttpRequest, name: str) -> bool:
    # A copied or imported study shares its recordings' files: any row of a study the
    # user may see that names the file is enough.
    studies = owned_studies(request)
    if Response.objects.filter(video=name, participant__study__in=studies).exists():
        return True
    names_it = Q.create([(field, name) for field in exchange.RECORDING_FILES], connector=Q.OR)
    if Recording.objects.filter(names_it, item__study__in=studies).exists():
        return True
    # A researcher's avatar (its file and preview stills) is theirs alone.
    avatars = (
        Avatar.objects.all()
        if request.user.is_superuser
        else Avatar.objects.filter(owner=request.user)
    )
    files = ("file", "still_rest", "still_letter", "still_face")
    return avatars.filter(Q.create([(f, name) for f in files], connector=Q.OR)).exists()


@require_safe
def private_media(request: HttpRequest, path: str) -> HttpResponse:
    """Send a personal file to a signed-in researcher of a study it belongs to."""
    user = request.user
    if not (user.is_authenticated and user.is_active and user.is_staff):
        raise Http404("No such file.")
    if not _may_open(request, path):
        raise Http404("No such file.")
    return _private_file(request, path)


@require_safe
def participant_answer_video(request: HttpRequest, token: str, response: int) -> HttpResponse:
    """Send a participant's own signed answer back to them while they take part."""
    found = (
        Response.objects.filter(
            pk=response, participant__token=token, participant__finished_at__isnull=True
        )
        .exclude(video="")
        .values_list("video", flat=True)
        .first()
    )
    if found is None:
        raise Http404("No such answer.")
    return _private_file(request, found)


@require_safe
def uploaded_clip(request: HttpRequest, path: str) -> HttpResponse:
    """Send an uploaded clip (or its poster) of a study that takes participants, or to
    a researcher of its study; to anyone else it does not exist.

    A researcher's unpublished material (a filmed signer, say) stays private until the
    study is in pilot or open; then it is served like a rendered clip, with ranges.
    """
    names_it = Q(video=path) | Q(poster=path)
    clips = UploadedClip.objects.filter(names_it)
    taking = (Study.Status.PILOT, Study.Status.OPEN)
    if clips.filter(condition__study__status__in=taking).exists():
        return _private_file(request, path, cache=UPLOADED_CACHE)
    user = request.user
    staff = user.is_authenticated and user.is_active and user.is_staff
    if staff and clips.filter(condition__study__in=owned_studies(request)).exists():
        return _private_file(request, path)
    raise Http404("No such file.")
