"""Build a study from scratch in the admin, in Chromium, and take it (issue 20's acceptance).

A researcher adds a study with two conditions and two items, sets each condition's
timing field by field, builds the pages with the design builder, generates the clips
in the background, pilots the study, opens it, a participant takes it, and the report
downloaded from the results page counts exactly what was clicked. No code or JSON is
edited anywhere.
"""

import io
import os
import zipfile
from pathlib import Path

import pytest
from playwright.sync_api import expect

from studyplatform.models import Condition, Participant, Stimulus, Study
from tests.studyplatform.taking import check_pair_wins, take_study

SCREENSHOTS = Path(__file__).resolve().parents[2] / "test-results"

pytestmark = pytest.mark.django_db(transaction=True)


def _sign_in(page, url: str) -> None:
    page.goto(f"{url}/admin/login/?next=/admin/studyplatform/study/add/")
    page.get_by_label("Username").fill("alice")
    page.get_by_label("Password").fill("pw-alice")
    page.get_by_role("button", name="Log in").click()


def _add_rows(page, name: str, rows: list[dict]) -> None:
    """Fill *rows* into the study page's inline *name* ("Condition", "Item")."""
    prefix = {"Condition": "conditions", "Item": "items"}[name]
    for index, values in enumerate(rows):
        page.get_by_role("button", name=f"Add another {name}").click()
        for field, value in values.items():
            page.locator(f'[name="{prefix}-{index}-{field}"]').fill(value)


def _set_timing(page, url: str, key: str, timing: str) -> None:
    condition = Condition.objects.get(key=key)
    page.goto(f"{url}/admin/studyplatform/condition/{condition.pk}/change/")
    page.get_by_label("Timing:", exact=True).select_option(timing)
    for label, value in (("Width:", "96"), ("Height:", "72"), ("Rate hz:", "20")):
        page.get_by_label(label, exact=True).fill(value)
    page.get_by_role("button", name="Save", exact=True).click()
    expect(page.locator(".messagelist .success")).to_be_visible()


def _set_status(page, url: str, study: Study, status: str) -> None:
    page.goto(f"{url}/admin/studyplatform/study/{study.pk}/change/")
    page.locator("#id_status").select_option(status)
    page.get_by_role("button", name="Save and continue editing").click()
    page.wait_for_load_state("load")
    errors = page.locator(".errorlist, .errornote").all_text_contents()
    assert not errors, errors
    expect(page.locator(".messagelist .success")).to_be_visible()


def _take(browser, url: str, slug: str) -> tuple[Participant, dict]:
    """Take the study as a new participant; return them and the clip clicked per page."""

    def answer(page, key: str, number: int) -> int:
        position = 1 if number % 2 else 2
        page.locator(f'input[name="q-more-natural"][value="{position}"]').check()
        return position

    return take_study(browser, url, slug, answer)


def test_a_study_built_from_scratch_is_generated_piloted_opened_taken_and_reported(
    page, browser, live_server, alice, settings, tmp_path, renderable
):
    settings.MEDIA_ROOT = tmp_path
    url = live_server.url
    _sign_in(page, url)
    page.get_by_label("Title").fill("Timing from scratch")
    page.get_by_label("Slug").fill("timing-from-scratch")
    _add_rows(
        page,
        "Condition",
        [{"key": "constant", "label": "Constant"}, {"key": "variable", "label": "Variable"}],
    )
    _add_rows(page, "Item", [{"key": "CAT", "text": "CAT"}, {"key": "DOG", "text": "DOG"}])
    page.get_by_role("button", name="Save and continue editing").click()
    page.wait_for_load_state("load")
    errors = page.locator(".errorlist, .errornote").all_text_contents()
    assert not errors, errors
    expect(page.locator(".messagelist .success")).to_be_visible()
    study = Study.objects.get(title="Timing from scratch")
    assert study.owner == alice and study.status == "draft"
    _set_timing(page, url, "constant", "constant")
    _set_timing(page, url, "variable", "variable")
    assert Condition.objects.get(key="variable").parameters["timing"] == "variable"

    # The design builder: the defaults (balanced pairs over everything) are what we want.
    page.goto(f"{url}/admin/studyplatform/study/{study.pk}/change/")
    page.locator(".object-tools").get_by_role("link", name="Design builder").click()
    page.get_by_label("Attention checks").fill("0")
    page.get_by_role("button", name="Build the pages").click()
    expect(page.locator("#summary-pages")).to_have_text("2")
    expect(page.locator("#summary-balance")).to_contain_text("Balanced")
    SCREENSHOTS.mkdir(exist_ok=True)
    page.screenshot(path=SCREENSHOTS / "admin-design-builder.png", full_page=True)

    # Generate: the progress page appears at once; a background process renders.
    page.get_by_role("link", name="Generate stimuli").first.click()
    page.get_by_role("button", name="Generate stimuli").click()
    expect(page.locator("#stimuli-bar")).to_be_visible()
    expect(page.locator("#stimuli-percent")).to_have_text("100", timeout=180_000)
    expect(page.locator("#stimuli-failed")).to_have_text("0")
    # Issue 35: at 100 % the page says so and what comes next; "being rendered" goes.
    expect(page.locator("#stimuli-done")).to_be_visible()
    expect(page.locator("#stimuli-done")).to_contain_text("Every clip is ready")
    expect(page.locator(".messagelist")).not_to_contain_text("being rendered")
    page.screenshot(path=SCREENSHOTS / "admin-stimuli-progress.png")

    _set_status(page, url, study, "pilot")
    pilot, _ = _take(browser, url, study.slug)
    assert pilot.is_pilot and pilot.is_finished
    _set_status(page, url, study, "open")
    participant, clicked = _take(browser, url, study.slug)
    assert not participant.is_pilot and participant.is_finished

    # The participants page lists both; the report counts the open participant only.
    page.goto(f"{url}/admin/studyplatform/study/{study.pk}/change/")
    page.locator(".object-tools").get_by_role("link", name="Participants").click()
    expect(page.locator("#roster tbody tr")).to_have_count(2)
    page.screenshot(path=SCREENSHOTS / "admin-participants.png", full_page=True)
    page.goto(f"{url}/admin/studyplatform/study/{study.pk}/change/")
    page.locator(".object-tools").get_by_role("link", name="Results").click()
    expect(page.get_by_text("1 of 2 participants analysed")).to_be_visible()
    with page.expect_download() as download:
        page.get_by_role("link", name="report (zip)").click()
    archive = zipfile.ZipFile(io.BytesIO(Path(download.value.path()).read_bytes()))
    # The report names conditions by their labels.
    pairs = check_pair_wins(archive, study, participant, clicked)
    assert int(pairs["n"]) == 2

    # Issue 35 (5): a new version renders none of the clips it shares with this one
    # (before, it said "0 are rendered" and rendered all of them again, overwriting).
    files = {s.video.path: os.stat(s.video.path).st_mtime_ns for s in Stimulus.objects.all()}
    page.goto(f"{url}/admin/studyplatform/study/{study.pk}/change/")
    page.get_by_role("button", name="Make a new version").click()
    page.wait_for_load_state("load")
    version = Study.objects.exclude(pk=study.pk).get()
    page.goto(f"{url}/admin/studyplatform/study/{version.pk}/stimuli/generate/")
    clips = page.locator("#generate-clips").inner_text()
    expect(page.locator("#generate-on-disk")).to_have_text(f"{clips} are ready")
    page.get_by_role("button", name="Generate stimuli").click()
    expect(page.locator("#stimuli-percent")).to_have_text("100")
    expect(page.locator("#stimuli-done")).to_be_visible()
    assert {p: os.stat(p).st_mtime_ns for p in files} == files
