"""Test the clips' own controls in Chromium: one tab stop each, keys, announced state, layout."""

import pytest
from playwright.sync_api import expect

from studyplatform.actions import do_enroll_participant
from studyplatform.models import Trial
from tests.conftest import close_context
from tests.studyplatform.test_participate_browser import _wait_ready, _with_clips

pytestmark = pytest.mark.django_db(transaction=True)


@pytest.fixture
def comparison_url(live_server, fingerspelling, clips_dir, one_clip):
    """The URL of a participant's first comparison page (two clips, one question)."""
    _with_clips(fingerspelling, one_clip, clips_dir)
    participant = do_enroll_participant(fingerspelling, consented=True)
    participant.reached = len(participant.schedule)
    participant.save()
    number = next(i for i, e in enumerate(participant.schedule, 1) if e["trial"] == "cmp-01")
    return f"{live_server.url}/p/{participant.token}/{number}/"


def _tab_stops_to_next(page) -> list[str]:
    """Return where Tab stops, from the top of the page to Next: "clip" inside a clip."""
    page.evaluate("document.activeElement.blur(); window.scrollTo(0, 0)")
    stops = []
    for _ in range(40):
        page.keyboard.press("Tab")
        stops.append(
            page.evaluate(
                "document.activeElement.closest('figure.clip') ? 'clip' : "
                "document.activeElement.id || document.activeElement.name || "
                "document.activeElement.className"
            )
        )
        if stops[-1] == "next-button":
            return stops
    raise AssertionError(f"Tab never reached Next: {stops}")


def test_each_clip_is_one_tab_stop_played_and_scrubbed_with_keys(page, comparison_url):
    page.goto(comparison_url)
    _wait_ready(page)
    assert page.evaluate(
        "Array.from(document.querySelectorAll('video.stimulus'))"
        ".every(v => !v.controls && v.tabIndex === -1)"
    )
    # Skip link, Clip 1, Clip 2, the answers (one radio group), Previous, Next: the
    # browser's control bars took 5 stops per clip (16 Tabs to Next, issue 20).
    stops = _tab_stops_to_next(page)
    assert stops.count("clip") == 2 and len(stops) <= 6, stops
    button = page.locator(".play-button").first
    button.focus()
    page.keyboard.press("Space")
    page.wait_for_function("!document.querySelector('video.stimulus').paused")
    expect(page.locator(".play-count").first).to_contain_text("Clip 1 playing")
    page.keyboard.press("Space")
    page.wait_for_function("document.querySelector('video.stimulus').paused")
    # The arrow keys ask the clip to move (headless Chromium reports the test server's
    # clips as not seekable, so the position itself is not checked here).
    page.evaluate(
        "window._seeks = 0; document.querySelector('video.stimulus')"
        ".addEventListener('seeking', () => window._seeks++)"
    )
    page.keyboard.press("ArrowRight")
    page.wait_for_function("window._seeks === 1")
    expect(page.locator(".play-count").first).to_contain_text("paused at")
    page.keyboard.press("Home")
    assert page.evaluate("document.querySelector('video.stimulus').currentTime") == 0
    assert page.evaluate("document.activeElement.classList.contains('play-button')")


@pytest.mark.parametrize(("width", "height"), [(390, 460), (844, 390)])
def test_two_clips_sit_side_by_side_on_a_phone(browser, comparison_url, width, height):
    """In landscape always; held upright where the study asks for it (issue 55: by default
    they stand one under the other there, tests/studyplatform/test_screens_browser.py)."""
    from studyplatform.models import Study

    Study.objects.filter(trials__key="cmp-01").update(phone_clips_side_by_side=height > width)
    context = browser.new_context(
        viewport={"width": width, "height": height}, bypass_csp=True, is_mobile=True, has_touch=True
    )
    try:
        page = context.new_page()
        page.goto(comparison_url)
        _wait_ready(page)
        first, second = (page.locator("figure.clip").nth(i).bounding_box() for i in (0, 1))
        assert abs(first["y"] - second["y"]) < 1 and second["x"] > first["x"] + first["width"] - 1
        if height > width:  # portrait: the clips stay in view while the questions scroll
            start = page.locator(".clips").bounding_box()["y"]
            room = page.evaluate("document.documentElement.scrollHeight - innerHeight")
            assert room > start + 40, (room, start)  # the page scrolls past the clips
            page.evaluate(f"window.scrollBy(0, {start + 40})")
            assert page.locator(".clips").bounding_box()["y"] == pytest.approx(0, abs=1)
    finally:
        close_context(context)
    assert Trial.objects.filter(key="cmp-01").exists()
