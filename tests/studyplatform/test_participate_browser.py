"""Take the demo studies in real headless Chromium, from the link to the completion code.

Issue 7's acceptance: a reload in the middle (resume, nothing lost or duplicated), a lost
connection during a save (retried), a double click on Next, keyboard-only operation and a
phone-sized window; the stored responses equal what was clicked. Every clip slot plays
one real rendered clip (rendering all 44 demo clips is the stimuli tests' business).
"""

import shutil
from pathlib import Path

import pytest
from playwright.sync_api import expect

from studyplatform.lib.stimuli import clip_spec, needed_pairs
from studyplatform.models import MediaEvent, Participant, Response, Stimulus, Trial
from tests.conftest import browser_context

SCREENSHOTS = Path(__file__).resolve().parents[2] / "test-results"

pytestmark = pytest.mark.django_db(transaction=True)


def _with_clips(study, clip, media_root: Path) -> None:
    """Give every clip slot of *study* the rendered clip, as a ready stimulus."""
    folder = media_root / "stimuli"
    folder.mkdir(parents=True, exist_ok=True)
    for path in (clip.video, clip.poster):  # full paths in the session's folder
        shutil.copy(path, folder / path.name)
    for condition, item in needed_pairs(study):
        Stimulus.objects.create(
            condition=condition,
            item=item,
            content_hash=clip_spec(condition, item).content_hash(),
            status=Stimulus.Status.READY,
            video=f"stimuli/{clip.video.name}",
            poster=f"stimuli/{clip.poster.name}",
            width=clip.width,
            height=clip.height,
            duration_ms=clip.duration_ms,
            frame_count=clip.frame_count,
        )


def _current(page):
    """Return (page number, trial key) of the page the browser shows."""
    form = page.locator("#page-form")
    return int(form.get_attribute("data-page")), form.get_attribute("data-trial")


def _wait_ready(page):
    page.wait_for_selector("#page-form.ready")


def _next(page, number, double=False):
    """Press Next on page *number* and wait for the following page (or the end)."""
    button = page.locator("#next-button")
    if double:
        button.dblclick()
    else:
        button.click()
    page.wait_for_function(
        f"!document.getElementById('page-form') || "
        f"Number(document.getElementById('page-form').dataset.page) !== {number}"
    )


def _answer_with_mouse(page, trial: Trial, clicked: dict) -> None:
    """Answer every question of *trial* on the page by clicking; note what was clicked."""
    for question in trial.questions.all():
        name = f"q-{question.key}"
        if question.kind == "pairwise":
            position = 2 if len(clicked) % 3 else 1
            page.locator(f'input[name="{name}"][value="{position}"]').check()
            clicked[(trial.key, question.key)] = position
        elif question.uses_options:
            values = list(question.options.order_by("position").values_list("value", flat=True))
            value = values[len(clicked) % len(values)]
            if trial.is_attention_check:  # pass it, so the analysis keeps this participant
                value = int(trial.expected_answer)
            page.locator(f'input[name="{name}"][value="{value}"]').check()
            clicked[(trial.key, question.key)] = value
        elif question.kind == "number":
            page.locator(f'input[name="{name}"]').fill("7")
            clicked[(trial.key, question.key)] = 7.0
        elif not question.is_personal:
            page.locator(f'[name="{name}"]').fill(f"answer to {question.key}")
            clicked[(trial.key, question.key)] = f"answer to {question.key}"


def _stored(participant) -> dict:
    stored = {}
    for response in Response.objects.filter(participant=participant).select_related(
        "trial", "question"
    ):
        question = response.question
        if question.kind == "pairwise":
            value = response.chosen_position
        elif question.uses_options:
            value = response.rating
        elif question.kind == "number":
            value = response.number
        else:
            value = response.text
        stored[(response.trial.key, question.key)] = value
    return stored


def test_fingerspelling_study_from_link_to_completion_code(
    page, live_server, fingerspelling, clips_dir, one_clip
):
    _with_clips(fingerspelling, one_clip, clips_dir)
    page.allowed_errors = [r"ERR_INTERNET_DISCONNECTED", r"Failed to fetch"]
    page.goto(f"{live_server.url}/s/{fingerspelling.slug}/?PROLIFIC_PID=pp-42")
    assert "Continuing means you agree" in page.content()
    SCREENSHOTS.mkdir(exist_ok=True)
    page.screenshot(path=SCREENSHOTS / "participant-welcome.png")
    page.get_by_role("button", name="Continue (I agree to take part)").click()
    participant = Participant.objects.get()
    assert participant.recruitment_params == {"PROLIFIC_PID": "pp-42"}
    total = len(participant.schedule)
    clicked: dict = {}
    number = 1
    dropped = False
    while True:
        _wait_ready(page)
        number, key = _current(page)
        trial = Trial.objects.get(study=fingerspelling, key=key)
        expect(page.get_by_text(f"Page {number} of {total}")).to_be_visible()
        if trial.item_id and trial.condition_a_id:
            video = page.locator("video.stimulus").first
            assert video.evaluate("v => v.readyState") >= 3  # preloaded before it shows
        if trial.item_id and number % 12 == 2:  # now and then, play a clip to its end
            page.locator(".play-button").first.click()
            page.wait_for_function("document.querySelector('video.stimulus').ended")
        _answer_with_mouse(page, trial, clicked)
        if number in (1, 2, 3) or key.startswith("attention") or number == 5:
            SCREENSHOTS.mkdir(exist_ok=True)
            name = "attention" if key.startswith("attention") else trial.kind
            page.screenshot(path=SCREENSHOTS / f"participant-{name}.png", full_page=True)
        if not dropped and number >= 5 and trial.kind == "pairwise":
            # The connection drops while an answer is saved: it is retried, then saved.
            # (A comparison page, never the attention check: changing that answer would
            # fail the check and exclude the participant from the analysis below.)
            dropped = True
            page.context.set_offline(True)
            question = trial.questions.get()
            changed = 1 if clicked[(key, question.key)] == 2 else 2
            page.locator(f'input[name="q-{question.key}"][value="{changed}"]').check()
            clicked[(key, question.key)] = changed
            page.get_by_text("Not saved yet (no connection)").wait_for()
            page.context.set_offline(False)
            page.get_by_text("Answer saved.").wait_for(timeout=15000)
            assert _stored(participant)[(key, question.key)] == changed
        if number == 20:
            # A reload in the middle: the same page comes back with its answer.
            page.wait_for_function(
                "document.getElementById('save-status').textContent === 'Answer saved.'"
            )
            page.reload()
            _wait_ready(page)
            assert _current(page) == (20, key)
            question = trial.questions.get()
            checked = page.locator(f'input[name="q-{question.key}"]:checked')
            assert int(checked.get_attribute("value")) == clicked[(key, question.key)]
        if number == 30:  # the personal link in a fresh tab resumes here too
            other = page.context.new_page()
            other.goto(f"{live_server.url}/p/{participant.token}/")
            assert other.locator("#page-form").get_attribute("data-page") == "30"
            other.close()
        _next(page, number, double=number in (10, 11))
        if number == total:
            break
    page.get_by_text("Your completion code").wait_for()
    assert page.locator("#completion-code").text_content() == "FSPELL-DEMO"
    participant.refresh_from_db()
    assert participant.is_finished
    assert _stored(participant) == clicked
    assert Response.objects.filter(participant=participant).count() == len(clicked)
    assert not Response.objects.filter(participant=participant, revision__gt=2).exists()
    kinds = set(MediaEvent.objects.filter(participant=participant).values_list("kind", flat=True))
    assert {"page_shown", "play", "ended"} <= kinds
    # And the data analyses: the 48 comparisons as this participant saw and chose them.
    from analysis import ReportOptions
    from studyplatform.lib import presented_conditions
    from studyplatform.lib.results import analyse_study

    results = analyse_study(fingerspelling, ReportOptions())
    assert results.report.pairwise.judgements == 48
    assert results.report.pairwise.participants == 1
    table = results.analysed[results.analysed["kind"] == "pairwise"]
    for row in table.itertuples():
        trial = Trial.objects.get(study=fingerspelling, key=row.trial)
        # The analysis names conditions by label, the simulated ones (the motion-capture
        # stand-in, the built-in Variable model's) "… (simulated)"; keys stay beside them.
        presented = presented_conditions(participant, trial)
        shown = [c.label + (" (simulated)" if c.simulated else "") for c in presented]
        assert [row.condition_a, row.condition_b] == shown
        assert [row.condition_a_key, row.condition_b_key] == [c.key for c in presented]
        assert row.chosen == shown[clicked[(row.trial, "most-natural")] - 1]
    SCREENSHOTS.mkdir(exist_ok=True)
    page.screenshot(path=SCREENSHOTS / "participant-done.png")


def _tab_to(page, selector: str, limit: int = 60) -> None:
    """Press Tab until the focused element matches *selector*."""
    for _ in range(limit):
        if page.evaluate(f"document.activeElement.matches({selector!r})"):
            return
        page.keyboard.press("Tab")
    raise AssertionError(f"Tab never reached {selector}")


def test_spine_study_by_keyboard_on_a_phone(browser, live_server, spine, clips_dir, one_clip):
    """Keyboard only, in a phone-sized window, ASL first: the whole study."""
    _with_clips(spine, one_clip, clips_dir)
    played = 0
    with browser_context(
        browser,
        viewport={"width": 390, "height": 844},
        is_mobile=True,
        bypass_csp=True,
        has_touch=True,
    ) as context:
        page = context.new_page()
        errors = []
        page.on("pageerror", lambda error: errors.append(str(error)))
        page.goto(f"{live_server.url}/s/{spine.slug}/")
        _tab_to(page, "button.button")
        page.keyboard.press("Enter")
        participant = None
        clicked: dict = {}
        while True:
            page.wait_for_selector("#page-form.ready, #completion-code")
            if page.locator("#completion-code").count():
                break
            participant = participant or Participant.objects.get()
            number, key = _current(page)
            trial = Trial.objects.get(study=spine, key=key)
            if trial.kind == "rating":
                SCREENSHOTS.mkdir(exist_ok=True)
                page.screenshot(path=SCREENSHOTS / "participant-phone-rating.png", full_page=True)
            # Nothing is wider than the phone's screen.
            assert page.evaluate("document.documentElement.scrollWidth") <= 390
            if trial.item_id and not played:  # the clip controls work from the keyboard
                _tab_to(page, ".play-button")
                page.keyboard.press("Enter")
                page.wait_for_function("document.querySelector('video.stimulus').ended")
                played += 1
            for question in trial.questions.order_by("position"):
                name = f"q-{question.key}"
                if question.kind == "open":
                    _tab_to(page, f'textarea[name="{name}"]')
                    page.keyboard.type("The shoulders moved.")
                    clicked[(key, question.key)] = "The shoulders moved."
                    continue
                if question.kind == "number":
                    _tab_to(page, f'input[name="{name}"]')
                    page.keyboard.type("12")
                    clicked[(key, question.key)] = 12.0
                    continue
                _tab_to(page, f'input[name="{name}"]')
                page.keyboard.press("Space")  # select the focused (first) option
                page.keyboard.press("ArrowRight")  # and move one on: selects the second
                clicked[(key, question.key)] = int(page.evaluate("document.activeElement.value"))
            _tab_to(page, "#next-button")
            # Focus is visible: the focused button has an outline.
            assert page.evaluate("getComputedStyle(document.activeElement).outlineStyle") != "none"
            page.keyboard.press("Enter")
            page.wait_for_function(
                f"!document.getElementById('page-form') || "
                f"Number(document.getElementById('page-form').dataset.page) !== {number}"
            )
        assert page.locator("#completion-code").text_content() == "SPINE-DEMO"
        SCREENSHOTS.mkdir(exist_ok=True)
        page.screenshot(path=SCREENSHOTS / "participant-phone-done.png", full_page=True)
    assert errors == []
    assert _stored(participant) == clicked


def _serious_violations(page) -> list[str]:
    from axe_playwright_python.sync_playwright import Axe

    results = Axe().run(page)
    return [
        f"{v['id']} ({v['impact']}): {v['help']} — {[n['target'] for n in v['nodes']][:3]}"
        for v in results.response["violations"]
    ]


@pytest.mark.parametrize(
    "layout",
    [{"width": 1280, "height": 800}, {"width": 390, "height": 844}],
    ids=["desktop", "phone"],
)
def test_every_page_type_passes_an_accessibility_scan(
    page, live_server, fingerspelling, spine, clips_dir, one_clip, layout
):
    """axe-core (4.12) finds no violation, of any impact, on any participant page,
    on a desktop and on a phone (where two clips sit side by side, sticky)."""
    from studyplatform.actions import do_enroll_participant

    page.set_viewport_size(layout)

    # On purpose: the refused Next (400) and the invalid link (404).
    page.allowed_errors = [r"(400|404).*/p/"]
    found = {}
    for study in (fingerspelling, spine):
        _with_clips(study, one_clip, clips_dir)
        page.goto(f"{live_server.url}/s/{study.slug}/")  # welcome and consent
        found[f"welcome ({study.slug})"] = _serious_violations(page)
        participant = do_enroll_participant(study, consented=True)
        participant.reached = len(participant.schedule)
        participant.save()
        kinds = {}
        for number, entry in enumerate(participant.schedule, 1):
            trial = Trial.objects.get(study=study, key=entry["trial"])
            kinds.setdefault(trial.kind, number)
        for kind, number in kinds.items():
            page.goto(f"{live_server.url}/p/{participant.token}/{number}/")
            _wait_ready(page)
            found[f"{kind} ({study.slug})"] = _serious_violations(page)
        # A page with an answer missing shows its error messages.
        page.goto(f"{live_server.url}/p/{participant.token}/1/")
        _wait_ready(page)
        page.locator("#next-button").click()
        page.locator(".question-error:not([hidden])").first.wait_for()
        found[f"errors ({study.slug})"] = _serious_violations(page)
        participant.finished_at = participant.consented_at
        participant.save()
        page.goto(f"{live_server.url}/p/{participant.token}/done/")
        found[f"thank-you ({study.slug})"] = _serious_violations(page)
    page.goto(f"{live_server.url}/p/not-a-token/")
    found["invalid link"] = _serious_violations(page)
    assert len(found) >= 14, sorted(found)
    # The scan does see problems: an unlabelled field is one.
    page.set_content('<!doctype html><html lang="en"><title>x</title><input type="text">')
    assert any(v.startswith("label (critical)") for v in _serious_violations(page))
    failing = {name: v for name, v in found.items() if v}
    assert failing == {}, "\n".join(f"{name}: {v}" for name, v in failing.items())


def open_trial_page(page, live_server, study, trial_key: str):
    """Enroll a participant who reached every page; open *trial_key*'s page; return them."""
    from studyplatform.actions import do_enroll_participant

    participant = do_enroll_participant(study, consented=True)
    participant.reached = len(participant.schedule)
    participant.save()
    number = next(i for i, e in enumerate(participant.schedule, 1) if e["trial"] == trial_key)
    page.goto(f"{live_server.url}/p/{participant.token}/{number}/")
    _wait_ready(page)
    return participant


def goto_trial_page(page, live_server, study, trial_key: str):
    """Enroll a participant who is on *trial_key*'s page (the furthest they reached) and
    open it; return them and the page number."""
    from studyplatform.actions import do_enroll_participant

    participant = do_enroll_participant(study, consented=True)
    number = next(i for i, e in enumerate(participant.schedule, 1) if e["trial"] == trial_key)
    participant.reached = participant.position = number
    participant.save()
    page.goto(f"{live_server.url}/p/{participant.token}/{number}/")
    return participant, number


def record_signed_answer(page, seconds: float = 1.5) -> None:
    """Record an answer with Chromium's synthetic camera, up to "Watch your recording"."""
    page.get_by_role("button", name="Record a signed answer").click()
    page.get_by_text("Recording…").wait_for()
    page.wait_for_timeout(1000 * seconds)
    page.get_by_role("button", name="Stop recording").click()
    page.get_by_text("Watch your recording").wait_for()


def test_a_signed_answer_is_recorded_and_sent_through_a_dropped_connection(
    page, live_server, spine, clips_dir, one_clip
):
    """The webcam (Chromium's synthetic camera) records an answer; it survives going offline."""
    _with_clips(spine, one_clip, clips_dir)
    page.allowed_errors = [r"ERR_INTERNET_DISCONNECTED", r"Failed to fetch"]
    participant = open_trial_page(page, live_server, spine, "comments")
    # Issue 20: .button's display overrode [hidden], showing both before any recording.
    expect(page.get_by_role("button", name="Stop recording")).to_be_hidden()
    expect(page.get_by_role("button", name="Send this recording")).to_be_hidden()
    record_signed_answer(page)
    page.context.set_offline(True)
    page.get_by_role("button", name="Send this recording").click()
    page.get_by_text("Connection lost").wait_for()
    page.context.set_offline(False)
    status = page.locator(".signed-status")
    expect(status).to_have_text("Your signed answer is saved.", timeout=20000)
    response = Response.objects.get(participant=participant, question__key="comments")
    assert response.video.name.endswith(".webm") and response.video.size > 1000
    assert response.video.open("rb").read(4) == b"\x1a\x45\xdf\xa3"
    # The page shows the saved answer after a reload, ready to be recorded again.
    page.reload()
    _wait_ready(page)
    # Played back through the participant's own private route, with byte ranges.
    src = page.locator(".signed-preview").get_attribute("src")
    assert src == f"/p/{participant.token}/answers/{response.pk}/video/"
    fetched = page.evaluate(
        "src => fetch(src, {headers: {Range: 'bytes=0-3'}})"
        ".then(r => [r.status, r.headers.get('content-type')])",
        src,
    )
    assert fetched == [206, "video/webm"]
    expect(page.get_by_role("button", name="Record again")).to_be_visible()


def test_replay_limit_and_watching_to_the_end(
    page, live_server, fingerspelling, clips_dir, one_clip
):
    """One play per clip; the answers open once both clips were watched to the end."""
    fingerspelling.replay_limit = 1
    fingerspelling.require_full_view = True
    fingerspelling.save()
    _with_clips(fingerspelling, one_clip, clips_dir)
    participant, number = goto_trial_page(page, live_server, fingerspelling, "cmp-01")
    before = page.locator(".clip-slot").first.bounding_box()
    _wait_ready(page)
    assert page.locator(".clip-slot").first.bounding_box() == before  # no layout jump
    choice = page.locator('input[name="q-most-natural"][value="1"]')
    assert choice.is_disabled()
    expect(page.get_by_text("watch each clip to its end")).to_be_visible()
    assert page.locator("video.stimulus").first.evaluate("v => v.controls") is False
    for clip in (1, 2):
        page.get_by_role("button", name=f"Play Clip {clip}").click()
        page.wait_for_function(f"document.querySelectorAll('video.stimulus')[{clip - 1}].ended")
        assert page.get_by_role("button", name="No plays left").nth(0).is_disabled()
    assert page.get_by_text("0 of 1 plays left").count() == 2
    choice.check()
    page.locator("#next-button").click()
    page.wait_for_function(f"document.getElementById('page-form').dataset.page !== '{number}'")
    participant.refresh_from_db()
    assert participant.position == number + 1
    ended = MediaEvent.objects.filter(participant=participant, kind="ended")
    assert sorted(ended.values_list("clip_position", flat=True)) == [1, 2]


def test_the_time_left_counts_down_and_the_page_closes_at_the_limit(
    page, live_server, fingerspelling
):
    """The timer turns prominent five minutes before the limit, and at the limit the page
    reloads into the server's "time is up" message."""
    from datetime import timedelta

    from django.utils import timezone

    from studyplatform.actions import do_enroll_participant

    page.allowed_errors = [r"\b410\b"]  # the closed page's status, expected at the end
    fingerspelling.time_limit_minutes = 20
    fingerspelling.save()
    participant = do_enroll_participant(fingerspelling, consented=True)
    url = f"{live_server.url}/p/{participant.token}/1/"
    Participant.objects.filter(pk=participant.pk).update(
        consented_at=timezone.now() - timedelta(minutes=15) + timedelta(seconds=2)
    )
    page.goto(url)
    timer = page.locator("#time-left")
    assert timer.text_content() == "5 minutes left" and "time-low" not in timer.get_attribute(
        "class"
    )
    page.wait_for_function("document.getElementById('time-left').classList.contains('time-low')")
    assert timer.text_content() == "4 minutes left"
    assert page.locator("#save-status").text_content() == "5 minutes left."
    Participant.objects.filter(pk=participant.pk).update(
        consented_at=timezone.now() - timedelta(minutes=20) + timedelta(seconds=2)
    )
    page.goto(url)
    assert timer.text_content() == "Less than a minute left"
    page.get_by_text("The time limit of 20 minutes has passed.").wait_for(timeout=10000)


@pytest.mark.parametrize(
    "viewport", [{"width": 390, "height": 844}, {"width": 1366, "height": 768}]
)
def test_a_slider_is_unanswered_until_touched(
    browser, live_server, spine, clips_dir, one_clip, viewport
):
    """Issue 57: a range input always holds a value, so a required slider must not send its
    starting point. Untouched, Next names the question; a keyboard move answers it."""
    from studyplatform.models import AnswerOption, Question

    with browser_context(
        browser, viewport=viewport, has_touch=viewport["width"] < 500, bypass_csp=True
    ) as context:
        page = context.new_page()
        spine.status = "draft"
        spine.save(update_fields=["status"])
        slider = Question.objects.create(
            study=spine, key="natural", kind="slider", text="How natural?"
        )
        AnswerOption.objects.create(
            question=slider, value=0, label="Not at all natural", position=0
        )
        AnswerOption.objects.create(
            question=slider, value=100, label="Completely natural", position=1
        )
        trial = spine.trials.get(key="rate-s1")
        trial.questions.set([slider])
        spine.status = "open"
        spine.save(update_fields=["status"])
        _with_clips(spine, one_clip, clips_dir)
        participant, number = goto_trial_page(page, live_server, spine, "rate-s1")
        _wait_ready(page)
        control = page.locator("#slider-natural")
        assert control.get_attribute("name") is None
        expect(page.locator("#slider-value-natural")).to_have_text(
            "Not answered yet: move or tap the slider."
        )
        page.locator("#next-button").click()
        expect(page.locator("#error-natural")).to_have_text("Please answer this question.")
        assert not Response.objects.filter(participant=participant, question=slider).exists()
        control.focus()
        for _ in range(3):
            page.keyboard.press("ArrowRight")
        expect(page.locator("#slider-value-natural")).to_have_text("53")
        expect(page.locator("#save-status")).to_have_text("Answer saved.")
        assert Response.objects.get(participant=participant, question=slider).rating == 53
        overflow = page.evaluate("document.documentElement.scrollWidth - window.innerWidth")
        assert overflow <= 0, overflow
        _next(page, number)
        page.go_back()
        _wait_ready(page)
        expect(page.locator("#slider-value-natural")).to_have_text("53")
        assert control.get_attribute("name") == "q-natural" and control.input_value() == "53"
