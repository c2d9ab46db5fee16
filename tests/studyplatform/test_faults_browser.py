"""The participant page's script under server faults, in real headless Chromium (issue 19).

Playwright's routing stands in for a server that fails (500) on some requests: a save is
retried with backoff and then left to the page's Next instead of forever, and an event
batch the server keeps failing on does not hold back the events behind it.
"""

import time

import pytest

from studyplatform.models import MediaEvent, Participant, PersonalAnswer
from tests.studyplatform.test_participate_browser import _next, _wait_ready, _with_clips

pytestmark = pytest.mark.django_db(transaction=True)

POISON = '"kind":"page_shown","page":2,'


def _until(page, condition, timeout_s: float = 30.0) -> None:
    """Wait for *condition*, letting Playwright run the route handlers meanwhile."""
    deadline = time.monotonic() + timeout_s
    while not condition():
        assert time.monotonic() < deadline, "timed out"
        page.wait_for_timeout(200)


def _fail(status: int, when=lambda body: True):
    def handle(route):
        if when(route.request.post_data or ""):
            route.fulfill(
                status=status,
                content_type="application/json",
                body='{"error": "simulated server fault"}',
            )
        else:
            route.continue_()

    return handle


def _consent_and_give_a_name(page, live_server, study) -> Participant:
    """Take *study*'s consent and type a name on its first page; return the participant."""
    page.goto(f"{live_server.url}/s/{study.slug}/")
    page.get_by_role("button", name="Continue (I agree to take part)").click()
    _wait_ready(page)
    participant = Participant.objects.get()
    page.locator('input[name="q-name"]').fill("Ann")
    page.locator('input[name="q-name"]').dispatch_event("change")
    return participant


def test_the_page_survives_server_errors(page, live_server, fingerspelling, clips_dir, one_clip):
    _with_clips(fingerspelling, one_clip, clips_dir)
    page.allowed_errors = [r"status of 500", r"HTTP 500"]
    # The second page's page_shown event fails on every try; the first page's answers too.
    page.route("**/events/", _fail(500, when=lambda body: POISON in body))
    page.route("**/answer/", _fail(500))
    participant = _consent_and_give_a_name(page, live_server, fingerspelling)
    page.get_by_text("Not saved yet (server error)").wait_for()
    # Five server errors (0.5 + 1 + 2 + 4 s of backoff), then the answer waits for Next.
    page.get_by_text("it is sent again when you go on").wait_for(timeout=20_000)
    assert page.locator("#save-status").text_content() == "Some answers are not saved yet."
    assert not PersonalAnswer.objects.exists()

    page.unroute("**/answer/")
    for question, value in (("age", "3"), ("asl-fluency", "1")):
        page.locator(f'input[name="q-{question}"][value="{value}"]').check()
    _next(page, 1)  # the form carries every answer, the failed one too
    assert PersonalAnswer.objects.get(participant=participant).value == "Ann"
    _wait_ready(page)

    # Playing a clip logs events behind the failing page_shown; they arrive all the same.
    # (The page stays put: a page's unload sends its events with keepalive, which
    # Playwright's routing does not see.)
    second = participant.schedule[1]["trial"]
    page.locator(".play-button").first.click()
    plays = MediaEvent.objects.filter(participant=participant, kind="play", trial__key=second)
    _until(page, plays.exists)
    shown = MediaEvent.objects.filter(participant=participant, kind="page_shown", trial__key=second)
    assert not shown.exists()
    page.unroute("**/events/")  # the server recovers: the held-back event arrives, once
    _until(page, shown.exists)
    # Events go one batch at a time, in order: once one logged after this (playing the
    # clip again) is in, anything sent again before it would be in too.
    page.wait_for_function("document.querySelector('video.stimulus').ended")
    page.locator(".play-button").first.click()
    _until(page, lambda: plays.count() == 2)
    assert shown.count() == 1


def test_a_save_still_on_its_way_never_lands_over_the_answer_next_carried(
    page, live_server, fingerspelling, clips_dir, one_clip, monkeypatch
):
    """Regression (found by a phone-keyboard test): an answer changed twice in a moment
    and Next pressed at once. The first save, slow at the server, landed after the page's
    form and put the older answer over the newer one the form carried, and the page was
    gone before the newer save was sent. Next now waits for the saves in flight."""
    import threading

    from studyplatform.views import participate

    _with_clips(fingerspelling, one_clip, clips_dir)
    arrived, release = threading.Event(), threading.Event()
    save = participate.do_save_response

    def slow_first_age(participant, trial, question, answer):
        if question.key == "age" and not arrived.is_set():
            arrived.set()
            release.wait(20)
        return save(participant, trial, question, answer)

    monkeypatch.setattr(participate, "do_save_response", slow_first_age)
    participant = _consent_and_give_a_name(page, live_server, fingerspelling)
    page.locator('input[name="q-asl-fluency"][value="1"]').check()
    page.get_by_text("Answer saved.").wait_for()
    # What the browser sent and when each answer came back, in order.
    timeline = []
    page.on("request", lambda r: timeline.append(("sent", r.method, r.url, r.post_data)))
    page.on(
        "response",
        lambda r: timeline.append(("answered", r.request.method, r.url, r.request.post_data)),
    )
    page.locator('input[name="q-age"][value="3"]').check()
    assert arrived.wait(10)  # the save of 3 is at the server, held there
    page.locator('input[name="q-age"][value="4"]').check()
    page.locator("#next-button").click()
    release.set()
    page.wait_for_function("Number(document.getElementById('page-form').dataset.page) === 2")
    # Next's form went only after the held save had ended (not after a guessed wait).

    held = next(
        i
        for i, (event, method, url, data) in enumerate(timeline)
        if event == "answered" and url.endswith("/answer/") and '"value":"3"' in (data or "")
    )
    form = next(
        i
        for i, (event, method, url, _) in enumerate(timeline)
        if event == "sent" and method == "POST" and url.rstrip("/").endswith("/1")
    )
    assert held < form, timeline
    stored = participant.responses.get(
        question__key="age", trial__key=participant.schedule[0]["trial"]
    )
    assert stored.rating == 4
