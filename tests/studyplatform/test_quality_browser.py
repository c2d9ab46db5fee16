"""Take a study in Chromium twice, carefully and as a speeder; the CSV says which was which.

Issue 20's acceptance: per-trial play counts and watched-to-end in the CSV match what
the browser did, and the speeder rule excludes a participant who answered before the
clips ended.
"""

import io
import time

import pandas as pd
import pytest

from analysis import ExclusionRules, apply_exclusions, read_responses
from analysis.exclusions import ANSWERED_EARLY
from studyplatform.lib.export import tidy_csv
from studyplatform.models import MediaEvent, Participant, Trial
from tests.conftest import close_context
from tests.studyplatform.test_participate_browser import _current, _next, _wait_ready, _with_clips

pytestmark = pytest.mark.django_db(transaction=True)


@pytest.fixture
def two_pages(fingerspelling, clips_dir, one_clip):
    """The fingerspelling demo cut to two comparisons and its closing page, with clips."""
    Trial.objects.filter(study=fingerspelling).exclude(
        key__in=["cmp-01", "cmp-02", "closing"]
    ).delete()
    _with_clips(fingerspelling, one_clip, clips_dir)
    return fingerspelling


def _wait_for_events(participant, kind: str, count: int, timeout_s: float = 20.0) -> None:
    """Wait until the browser's batched events reached the server."""
    deadline = time.monotonic() + timeout_s
    while time.monotonic() < deadline:
        if MediaEvent.objects.filter(participant=participant, kind=kind).count() >= count:
            return
        time.sleep(0.3)
    found = MediaEvent.objects.filter(participant=participant, kind=kind).count()
    raise AssertionError(f"only {found} {kind} events reached the server")


def _play_to_end(page, clip: int) -> None:
    page.locator(".play-button").nth(clip - 1).click()
    page.wait_for_function(f"document.querySelectorAll('video.stimulus')[{clip - 1}].ended")


def _take(page, url: str, study, careful: bool) -> tuple[Participant, dict]:
    """Take the study; the careful participant watches, and replays clip 1 on page 1."""
    page.goto(url)
    page.get_by_role("button", name="Continue (I agree to take part)").click()
    participant = Participant.objects.filter(study=study).order_by("-pk").first()
    played: dict = {}
    while True:
        _wait_ready(page)
        number, key = _current(page)
        if key == "closing":
            if careful:
                _wait_for_events(participant, "ended", 5)
            else:
                _wait_for_events(participant, "page_shown", 3)
            _next(page, number)
            break
        if careful:
            _play_to_end(page, 1)
            _play_to_end(page, 2)
            plays = {1: 1, 2: 1}
            if number == 1:
                _play_to_end(page, 1)
                plays[1] = 2
            played[key] = plays
        page.locator('input[name="q-most-natural"][value="1"]').check()
        page.get_by_text("Answer saved.").wait_for()
        _next(page, number)
    page.get_by_text("Your completion code").wait_for()
    return participant, played


def test_play_counts_and_ends_match_the_browser_and_the_speeder_is_excluded(
    browser, live_server, two_pages
):
    url = f"{live_server.url}/s/{two_pages.slug}/"
    results = {}
    for careful in (True, False):
        context = browser.new_context(viewport={"width": 1280, "height": 800}, bypass_csp=True)
        try:
            results[careful] = _take(context.new_page(), url, two_pages, careful)
        finally:
            close_context(context)
    (watcher, played), (speeder, _) = results[True], results[False]
    text = tidy_csv(two_pages)
    frame = pd.read_csv(io.StringIO(text), dtype=str, keep_default_na=False)
    rows = frame[frame["trial"].str.startswith("cmp-")].set_index(["participant", "trial"])
    for key, plays in played.items():
        row = rows.loc[(str(watcher.pk), key)]
        assert (int(row.clip1_plays), int(row.clip2_plays)) == (plays[1], plays[2])
        assert (row.clip1_ended, row.clip2_ended, row.answered_before_end) == ("1", "1", "0")
        assert int(row.replays) == plays[1] - 1
        assert int(row.time_on_page_ms) > 0 and row.viewport == "1280x800"
        assert row.device == "desktop" and row.playback_errors == "0"
    assert {int(rows.loc[(str(watcher.pk), key)].page_order) for key in played} == {1, 2}
    for key in ("cmp-01", "cmp-02"):
        row = rows.loc[(str(speeder.pk), key)]
        assert (row.clip1_plays, row.clip2_plays, row.clip1_ended, row.clip2_ended) == (
            "0",
            "0",
            "0",
            "0",
        )
        assert row.answered_before_end == "1" and row.shown_at
    table = read_responses(io.StringIO(text))
    kept, report = apply_exclusions(table, ExclusionRules(answered_before_end=True))
    assert set(kept["participant"]) == {str(watcher.pk)}
    assert report.excluded_participants == {str(speeder.pk): [ANSWERED_EARLY]}
    # The report summarizes the same per participant (the results page shows it).
    from analysis import ReportOptions
    from studyplatform.lib.results import analyse_study

    quality = {q.participant: q for q in analyse_study(two_pages, ReportOptions()).report.quality}
    assert quality[str(watcher.pk)].clips_ended_share == 1.0
    assert quality[str(watcher.pk)].replays == 1 and quality[str(watcher.pk)].device == "desktop"
    assert quality[str(speeder.pk)].clips_ended_share == 0.0
    assert quality[str(speeder.pk)].answered_before_end == 2


def test_a_reloaded_page_answered_after_its_clips_is_not_flagged(browser, live_server, two_pages):
    """Issue 35: a page shown twice (reload) counts from the showing the answer was given in.

    Page 1: shown, reloaded 3 s later, both clips played to the end, answered: not early.
    Page 2: answered at once, before either clip played: still early.
    """
    context = browser.new_context(viewport={"width": 1280, "height": 800}, bypass_csp=True)
    try:
        page = context.new_page()
        page.goto(f"{live_server.url}/s/{two_pages.slug}/")
        page.get_by_role("button", name="Continue (I agree to take part)").click()
        participant = Participant.objects.filter(study=two_pages).order_by("-pk").first()
        _wait_ready(page)
        number, first = _current(page)
        _wait_for_events(participant, "page_shown", 1)
        time.sleep(3)
        page.reload()
        _wait_ready(page)
        _play_to_end(page, 1)
        _play_to_end(page, 2)
        page.locator('input[name="q-most-natural"][value="1"]').check()
        page.get_by_text("Answer saved.").wait_for()
        _next(page, number)
        _wait_ready(page)
        number, second = _current(page)
        page.locator('input[name="q-most-natural"][value="2"]').check()
        page.get_by_text("Answer saved.").wait_for()
        _next(page, number)
        _wait_for_events(participant, "ended", 2)
        _wait_for_events(participant, "page_shown", 3)
    finally:
        close_context(context)
    frame = pd.read_csv(io.StringIO(tidy_csv(two_pages)), dtype=str, keep_default_na=False)
    rows = frame[frame["participant"].eq(str(participant.pk))].set_index("trial")
    assert (
        MediaEvent.objects.filter(
            participant=participant, trial__key=first, kind="page_shown"
        ).count()
        == 2
    )
    assert (rows.loc[first, "clip1_ended"], rows.loc[first, "clip2_ended"]) == ("1", "1")
    assert rows.loc[first, "answered_before_end"] == "0"
    assert rows.loc[second, "answered_before_end"] == "1"
