"""Take a participant's signed answer: a webcam recording sent in resumable chunks."""

from django.core.exceptions import ValidationError
from django.http import HttpRequest, JsonResponse
from django.utils.translation import gettext
from django.views.decorators.cache import never_cache
from django.views.decorators.http import require_http_methods

from studyplatform.actions.uploads import (
    UploadOffsetMismatch,
    UploadRejected,
    do_append_signed_answer_chunk,
    parse_final,
    take_id,
    upload_offset,
)
from studyplatform.lib import page_trial, participant_by_token
from studyplatform.views.language import in_study_language, speak

UPLOAD_CONTENT_TYPES = ("application/octet-stream", "video/webm", "video/mp4")


@never_cache
@require_http_methods(["GET", "POST"])
@in_study_language
def upload_signed_answer(
    request: HttpRequest, token: str, number: int, question: str
) -> JsonResponse:
    """Take a chunk of a webcam recording (POST), or say how much of a take is stored (GET).

    Headers ``X-Upload-Take`` (the take's UUID; ``?take=`` on GET), ``X-Upload-Offset``
    (where the chunk starts), and on the last chunk ``X-Upload-Final: 1`` with
    ``X-Upload-Sha256`` (of the whole file) and optionally ``X-Upload-Duration-Ms``; a
    chunk at the wrong offset gets 409 and the offset to resume from.
    """
    participant = participant_by_token(token)
    if participant is None:
        return JsonResponse({"error": gettext("This link is not valid.")}, status=404)
    speak(request, participant.study)
    try:
        trial = page_trial(participant, number, for_answer=True)
        found = next((q for q in trial.questions.all() if q.key == question), None)
        if found is None:
            raise UploadRejected(
                gettext("“%(question)s” is not asked on this page.") % {"question": question}
            )
        if request.method == "GET":
            take = take_id(request.GET.get("take"))
            return JsonResponse({"offset": upload_offset(participant, trial, found, take)})
        if request.content_type not in UPLOAD_CONTENT_TYPES:
            sent = request.content_type or "nothing"
            message = f"A recording is sent as application/octet-stream, not “{sent}”."
            return JsonResponse({"error": message}, status=415)
        offset_text = request.headers.get("X-Upload-Offset", "")
        if not (offset_text.isascii() and offset_text.isdigit() and len(offset_text) < 16):
            raise UploadRejected("The chunk does not say where it starts.")
        final = None
        if request.headers.get("X-Upload-Final") == "1":
            final = parse_final(
                request.headers.get("X-Upload-Sha256"), request.headers.get("X-Upload-Duration-Ms")
            )
        stored, response = do_append_signed_answer_chunk(
            participant,
            trial,
            found,
            request.headers.get("X-Upload-Take", ""),
            int(offset_text),
            request.body,
            final,
        )
    except UploadOffsetMismatch as mismatch:
        return JsonResponse({"error": mismatch.messages[0], "offset": mismatch.offset}, status=409)
    except ValidationError as error:
        return JsonResponse({"error": error.messages[0]}, status=400)
    return JsonResponse({"offset": stored, "saved": response is not None})
