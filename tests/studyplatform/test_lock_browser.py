"""An answered study stays locked whatever its status says (issue 35, point 2), in Chromium.

Before: close it, set Status back to Draft, Save — the lock notice went, the conditions
became editable (a hold changed from 400 to 450 ms was accepted) and "Build the pages"
came back.
"""

import pytest
from playwright.sync_api import expect

from studyplatform.actions import Answer, do_enroll_participant, do_save_response
from studyplatform.models import Condition, Study
from tests.conftest import close_context

pytestmark = pytest.mark.django_db(transaction=True)


@pytest.fixture
def answered(fingerspelling):
    """The fingerspelling study, opened, taken by one participant, and closed."""
    fingerspelling.status = Study.Status.OPEN
    fingerspelling.save()
    participant = do_enroll_participant(fingerspelling)
    trial = fingerspelling.trials.get(key=participant.schedule[0]["trial"])
    question = trial.questions.filter(is_personal=False).first()
    do_save_response(participant, trial, question, Answer(rating=3, number=3, text="3"))
    fingerspelling.status = Study.Status.CLOSED
    fingerspelling.save()
    return fingerspelling


def _sign_in(page, url: str) -> None:
    page.goto(f"{url}/admin/login/")
    page.get_by_label("Username").fill("alice")
    page.get_by_label("Password").fill("pw-alice")
    page.get_by_role("button", name="Log in").click()


def test_status_back_to_draft_does_not_unlock_an_answered_study(browser, live_server, answered):
    url = live_server.url
    condition = Condition.objects.filter(study=answered).first()
    context = browser.new_context(viewport={"width": 1280, "height": 900})
    try:
        page = context.new_page()
        _sign_in(page, url)
        page.goto(f"{url}/admin/studyplatform/study/{answered.pk}/change/")
        page.locator("#id_status").select_option("draft")
        page.get_by_role("button", name="Save and continue editing").click()
        page.wait_for_load_state("load")
        expect(page.locator(".errorlist")).to_contain_text("cannot go back to draft or pilot")
        answered.refresh_from_db()
        assert answered.status == Study.Status.CLOSED
        # Even with the status forced to draft behind the admin's back, the data lock it.
        Study.objects.filter(pk=answered.pk).update(status=Study.Status.DRAFT)
        page.goto(f"{url}/admin/studyplatform/study/{answered.pk}/change/")
        expect(page.locator("#design-locked-note")).to_contain_text("1 participant has taken it")
        page.goto(f"{url}/admin/studyplatform/condition/{condition.pk}/change/")
        expect(page.get_by_role("button", name="Save", exact=True)).to_have_count(0)
        page.goto(f"{url}/admin/studyplatform/study/{answered.pk}/design/")
        expect(page.locator("#design-locked")).to_contain_text("1 participant has taken it")
        expect(page.get_by_role("button", name="Build the pages")).to_have_count(0)
    finally:
        close_context(context)


@pytest.mark.parametrize("width", [1024, 1280, 1366, 1920])
def test_make_a_new_version_can_be_clicked_at_every_desktop_width(
    browser, live_server, answered, width
):
    """Issue 35, point 4: at 1024–1366 px a click on the button landed on "Export…"."""
    context = browser.new_context(viewport={"width": width, "height": 900})
    try:
        page = context.new_page()
        _sign_in(page, live_server.url)
        page.goto(f"{live_server.url}/admin/studyplatform/study/{answered.pk}/change/")
        button = page.get_by_role("button", name="Make a new version")
        box = button.bounding_box()
        on_top = page.evaluate(
            "([x, y]) => document.elementFromPoint(x, y)?.value || ''",
            [box["x"] + box["width"] / 2, box["y"] + box["height"] / 2],
        )
        assert on_top == "Make a new version"
        button.click()
        page.wait_for_load_state("load")
        assert Study.objects.count() == 2  # the new version, a draft copy
    finally:
        close_context(context)
