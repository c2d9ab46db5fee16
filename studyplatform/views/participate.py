"""Take a study: welcome and consent, the scheduled pages, saving answers, thank-you.

A participant is known by the token in their link (``/p/<token>/``), which is also
remembered in the browser session, so the study's own link (``/s/<slug>/``) leads back
to where they stopped. Every answer is saved as soon as it is given (``answer/``, JSON)
and again with the page's form; both are idempotent, so a reload, a double click or a
re-posted form neither loses nor duplicates anything. No participant response may be
cached (``Cache-Control: no-store``, Django's never_cache): a lab's shared computer keeps
no copy of someone's answers, and a back button asks the server again.
"""

from django.core.exceptions import ValidationError
from django.http import HttpRequest, HttpResponse, JsonResponse
from django.shortcuts import redirect, render
from django.urls import reverse
from django.utils.translation import gettext
from django.views.decorators.cache import never_cache
from django.views.decorators.http import require_http_methods, require_POST

from studyplatform.actions import (
    AnswerRejected,
    EventsRejected,
    PageRejected,
    do_advance_participant,
    do_enroll_participant,
    do_go_back_participant,
    do_log_media_events,
    do_save_page_answers,
    do_save_response,
    do_set_participant_language,
)
from studyplatform.lib import (
    TIME_LOW,
    closed_reason,
    completion_url,
    device_problem,
    page_count,
    page_trial,
    participant_by_token,
    time_left,
    unwatched_clips,
)
from studyplatform.lib.pages import participant_page, study_asl
from studyplatform.models import Participant, Study, Trial
from studyplatform.models.participants import PARTICIPANT_SESSION_KEY
from studyplatform.views.language import in_study_language, speak
from studyplatform.views.posted import (
    BodyRejected,
    json_body,
    page_number,
    parse_answer,
    reached_page,
)

SESSION_KEY = PARTICIPANT_SESSION_KEY
NEW_PARTICIPANT_PARAM = "new"


def _invalid_link() -> JsonResponse:
    """Answer a script that sent an unknown participant token."""
    return JsonResponse({"error": gettext("This link is not valid.")}, status=404)


def _wants_json(request: HttpRequest) -> bool:
    return "application/json" in request.headers.get("Accept", "")


def _problem(request: HttpRequest, message: str, status: int = 400, **context) -> HttpResponse:
    """Answer with *message*: JSON for the page's script, else a page that says it."""
    if _wants_json(request) or request.content_type == "application/json":
        return JsonResponse({"error": message, **context}, status=status)
    return render(
        request, "studyplatform/participate/problem.html", {"message": message}, status=status
    )


def forget_in_browser(request: HttpRequest, slug: str, token: str) -> None:
    """Forget the participant *token* in this browser: the study's link starts afresh."""
    remembered = request.session.get(SESSION_KEY, {})
    if remembered.get(slug) == token:
        del remembered[slug]
        request.session.modified = True


def _page_url(participant: Participant, number: int) -> str:
    if number > page_count(participant) or participant.is_finished:
        return reverse("participant_done", args=[participant.token])
    return reverse("participant_page", args=[participant.token, number])


@never_cache
@require_http_methods(["GET", "POST"])
@in_study_language
def study_welcome(request: HttpRequest, slug: str) -> HttpResponse:
    """Show the study's welcome and consent page; starting enrolls the participant."""
    study = Study.objects.filter(slug=slug).first()
    if study is None:
        return _problem(request, gettext("There is no study at this address."), status=404)
    speak(request, study)
    returning = _returning_participant(request, study)
    if returning is not None:
        return redirect(_page_url(returning, returning.position))
    if not study.is_accepting_participants:
        return _problem(request, gettext("This study is not taking participants now."), status=410)
    device = device_problem(study, request.headers.get("User-Agent", ""))
    error = ""
    if request.method == "POST" and not device:
        agreed = request.POST.get("consent") == "yes"
        if study.consent_mode == Study.ConsentMode.EXPLICIT and not agreed:
            error = gettext("Please tick the box to agree before you start.")
        else:
            return _enroll(request, study)
    language = Participant.Language.ASL_ENGLISH if study.asl_first else Participant.Language.ENGLISH
    return render(
        request,
        "studyplatform/participate/welcome.html",
        {
            "study": study,
            "asl": study_asl(study, language),
            "device_problem": device,
            "error": error,
            "query": request.GET.urlencode(),
        },
        status=400 if error else 200,
    )


def _returning_participant(request: HttpRequest, study: Study) -> Participant | None:
    """Return the participant this browser already enrolled in *study*, to resume, or None.

    On a shared computer, ?new=1 starts the next participant even when the one before
    left without finishing (the researcher's way to clear the computer), and a finished
    participant's link is the next one's start.
    """
    fresh = study.shared_computer and request.GET.get(NEW_PARTICIPANT_PARAM) == "1"
    known = None if fresh else request.session.get(SESSION_KEY, {}).get(study.slug)
    participant = participant_by_token(known) if known else None
    if participant is None or (study.shared_computer and participant.is_finished):
        return None
    return participant


def _enroll(request: HttpRequest, study: Study) -> HttpResponse:
    """Enroll a participant who agreed, remember them in the session, go to page 1."""
    params = request.GET.dict()
    params.pop(NEW_PARTICIPANT_PARAM, None)
    try:
        participant = do_enroll_participant(
            study,
            recruitment_params=params,
            user_agent=request.headers.get("User-Agent", ""),
            consented=True,
        )
    except ValidationError as problem:
        return _problem(request, problem.messages[0], status=410)
    request.session.setdefault(SESSION_KEY, {})[study.slug] = participant.token
    request.session.modified = True
    return redirect(_page_url(participant, 1))


@never_cache
@in_study_language
def resume(request: HttpRequest, token: str) -> HttpResponse:
    """Send the participant to the page they are on."""
    participant = participant_by_token(token)
    if participant is None:
        return _problem(request, gettext("This link is not valid."), status=404)
    speak(request, participant.study)
    return redirect(_page_url(participant, max(participant.position, 1)))


def _save_form_answers(participant: Participant, trial: Trial, post) -> dict[str, str]:
    """Save every answer the page's form holds; return the errors by question key."""
    errors, answers = {}, {}
    for question in trial.questions.all():
        value = post.get(f"q-{question.key}")
        if not value:
            continue  # unanswered (a required question is caught on moving on)
        try:
            answers[question] = parse_answer(
                question,
                value,
                post.get(f"rt-{question.key}"),
                post.get(f"client-{question.key}"),
            )
        except AnswerRejected as error:
            errors[question.key] = error.messages[0]
    if answers:
        try:
            errors.update(do_save_page_answers(participant, trial, answers))
        except AnswerRejected as error:  # the page itself: not the study's, or finished
            errors.update({question.key: error.messages[0] for question in answers})
    return errors


@never_cache
@require_http_methods(["GET", "POST"])
@in_study_language
def page(request: HttpRequest, token: str, number: int) -> HttpResponse:
    """Show page *number*; its form saves the answers and moves on (or back)."""
    participant = participant_by_token(token)
    if participant is None:
        return _problem(request, gettext("This link is not valid."), status=404)
    speak(request, participant.study)
    refused = _refuse_page(request, participant, number)
    if refused is not None:
        return refused
    try:
        trial = page_trial(participant, number)
    except PageRejected as error:
        if request.method == "GET":
            return redirect(_page_url(participant, max(participant.position, 1)))
        return _problem(request, error.messages[0])
    errors: dict[str, str] = {}
    if request.method == "POST":
        moved_or_errors = _submit_page(request, participant, number, trial)
        if isinstance(moved_or_errors, HttpResponse):
            return moved_or_errors
        errors = moved_or_errors
    return _render_page(request, participant, number, trial, errors)


def _refuse_page(request: HttpRequest, participant: Participant, number: int):
    """Return where a participant who may not see page *number* now goes, or None."""
    if participant.is_finished:
        return redirect(_page_url(participant, number))
    reason = closed_reason(participant)
    if reason:
        return _problem(request, reason, status=410)
    earlier = number != participant.position and not participant.study.allow_back
    if request.method == "GET" and earlier:
        return redirect(_page_url(participant, participant.position))
    return None


def _submit_page(request: HttpRequest, participant: Participant, number: int, trial: Trial):
    """Save the page's form and move on (or back): the move's answer, or else the errors
    to show on the page (a JSON answer naming them for the page's script)."""
    if number < participant.position and not participant.study.allow_back:
        # A re-posted earlier page (double click, back button): already moved on.
        return _moved(request, participant, participant.position)
    errors = _save_form_answers(participant, trial, request.POST)
    if not errors:
        try:
            if request.POST.get("nav") == "back":
                target = do_go_back_participant(participant, number - 1)
            else:
                target = do_advance_participant(participant, number, trial)
            return _moved(request, participant, target)
        except PageRejected as error:
            missing = error.params.get("questions", []) if error.params else []
            errors = {key: gettext("Please answer this question.") for key in missing}
            errors["__page__"] = error.messages[0]
    if _wants_json(request):
        message = errors.get("__page__") or gettext("Some answers could not be saved.")
        questions = {key: text for key, text in errors.items() if key != "__page__"}
        return JsonResponse({"error": message, "questions": questions}, status=400)
    return errors


def _render_page(
    request: HttpRequest,
    participant: Participant,
    number: int,
    trial: Trial,
    errors: dict[str, str],
) -> HttpResponse:
    """Render page *number* with *errors* (400 when there are any)."""
    study = participant.study
    page_shown = participant_page(participant, number, trial)
    watched = []
    if study.require_full_view and page_shown.clips:
        unwatched = unwatched_clips(participant, trial)
        watched = [clip.number for clip in page_shown.clips if clip.number not in unwatched]
    context = {
        "participant": participant,
        "study": study,
        "page": page_shown,
        "asl": page_shown.asl,
        "watched": watched,
        "errors": errors,
        "page_error": errors.get("__page__", ""),
        "can_go_back": study.allow_back and number > 1,
        "seconds_left": _seconds(time_left(participant)),
        "low_seconds": _seconds(TIME_LOW),
    }
    template = "studyplatform/participate/page.html"
    return render(request, template, context, status=400 if errors else 200)


def _seconds(left) -> int | None:
    return None if left is None else int(left.total_seconds())


def _moved(request: HttpRequest, participant: Participant, target: int) -> HttpResponse:
    url = _page_url(participant, target)
    if _wants_json(request):
        return JsonResponse({"url": url})
    return redirect(url)


@never_cache
@require_POST
@in_study_language
def save_answer(request: HttpRequest, token: str) -> JsonResponse:
    """Save one answer now (JSON ``{page, trial, question, value, rt_ms, client_ms}``)."""
    participant = participant_by_token(token)
    if participant is None:
        return _invalid_link()
    speak(request, participant.study)
    try:
        data = json_body(request)
    except BodyRejected as error:
        return JsonResponse({"error": str(error)}, status=error.status)
    if not isinstance(data, dict) or page_number(data.get("page")) is None:
        return JsonResponse(
            {"error": gettext("The answer is not in the expected form.")}, status=400
        )
    try:
        trial = page_trial(participant, data["page"], for_answer=True)
        if data.get("trial") != trial.key:
            raise AnswerRejected(gettext("This answer belongs to another page."))
        question = next((q for q in trial.questions.all() if q.key == data.get("question")), None)
        if question is None:
            raise AnswerRejected(
                gettext("“%(question)s” is not asked on this page.")
                % {"question": data.get("question")}
            )
        answer = parse_answer(question, data.get("value"), data.get("rt_ms"), data.get("client_ms"))
        saved = do_save_response(participant, trial, question, answer)
    except ValidationError as error:
        return JsonResponse({"error": error.messages[0]}, status=400)
    return JsonResponse({"saved": True, "revision": getattr(saved, "revision", 1)})


@never_cache
@require_POST
@in_study_language
def log_events(request: HttpRequest, token: str) -> JsonResponse:
    """Log a batch of media and page events (JSON ``{"events": [...]}``)."""
    participant = participant_by_token(token)
    if participant is None:
        return _invalid_link()
    speak(request, participant.study)
    try:
        data = json_body(request, strip_nul=False)
    except BodyRejected as error:
        return JsonResponse({"error": str(error)}, status=error.status)
    events = data.get("events") if isinstance(data, dict) else None
    try:
        logged = do_log_media_events(participant, events)
    except EventsRejected as error:
        return JsonResponse({"error": error.messages[0]}, status=400)
    return JsonResponse({"logged": logged})


@never_cache
@require_POST
@in_study_language
def set_language(request: HttpRequest, token: str) -> HttpResponse:
    """Switch between ASL + English and English only, then show the same page."""
    participant = participant_by_token(token)
    if participant is None:
        return _problem(request, gettext("This link is not valid."), status=404)
    speak(request, participant.study)
    try:
        do_set_participant_language(participant, request.POST.get("language", ""))
    except ValidationError as error:
        return _problem(request, error.messages[0])
    # Back to the page it was made on: by Back or a link, not always their position.
    shown = reached_page(request.POST.get("page", ""), participant.reached)
    return redirect(_page_url(participant, shown or max(participant.position, 1)))


REDIRECT_AFTER_S = 8


@never_cache
@in_study_language
def done(request: HttpRequest, token: str) -> HttpResponse:
    """Thank the participant: the completion code, or the way back to the recruiter."""
    participant = participant_by_token(token)
    if participant is None:
        return _problem(request, gettext("This link is not valid."), status=404)
    speak(request, participant.study)
    if not participant.is_finished:
        return redirect(_page_url(participant, max(participant.position, 1)))
    study = participant.study
    if study.shared_computer:
        forget_in_browser(request, study.slug, participant.token)
    return render(
        request,
        "studyplatform/participate/done.html",
        {
            "participant": participant,
            "study": study,
            "asl": study_asl(study, participant.language),
            "redirect": completion_url(participant) if study.redirect_url else "",
            # Long enough to read (or copy) the code, short enough not to be left waiting.
            "redirect_after_s": REDIRECT_AFTER_S,
        },
    )
