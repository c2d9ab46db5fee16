"""The pages work under their Content-Security-Policy in real Chromium (issue 19).

The other browser tests bypass the policy (Playwright evaluates their string predicates
with eval); this one keeps it, takes pages with clips, a signed answer's recorder and
an admin page with an inline script, and fails on any violation the browser reports.
"""

import pytest
from django.urls import reverse

from studyplatform.models import Participant, Response
from tests.conftest import close_context
from tests.studyplatform.test_participate_browser import _with_clips

pytestmark = pytest.mark.django_db(transaction=True)


@pytest.fixture
def strict_page(browser, _django_db_helper):
    """A browser page that enforces the site's policy and collects its violations."""
    context = browser.new_context(viewport={"width": 1280, "height": 900})
    page = context.new_page()
    page.violations = []
    page.on(
        "console",
        lambda msg: "Content Security Policy" in msg.text and page.violations.append(msg.text),
    )
    page.on("pageerror", lambda error: page.violations.append(str(error)))
    yield page
    close_context(context)


def test_participant_and_admin_pages_run_under_the_policy(
    strict_page, live_server, alice, fingerspelling, clips_dir, one_clip
):
    page = strict_page
    _with_clips(fingerspelling, one_clip, clips_dir)
    page.goto(f"{live_server.url}/s/{fingerspelling.slug}/")
    page.get_by_role("button", name="Continue (I agree to take part)").click()
    page.wait_for_selector("#page-form.ready")  # the page's script ran
    page.locator('input[name="q-age"][value="2"]').check()
    page.locator('input[name="q-asl-fluency"][value="1"]').check()
    page.get_by_text("Answer saved.").wait_for()  # fetch() to the site is allowed
    page.locator("#next-button").click()
    page.wait_for_selector('#page-form.ready[data-page="2"]')
    page.locator(".play-button").first.click()  # a clip from the site's media plays
    page.wait_for_selector("video.stimulus")
    participant = Participant.objects.get()
    assert Response.objects.filter(participant=participant, question__key="age").exists()

    page.context.add_cookies(
        [{"name": "sessionid", "value": _session_of(alice), "url": live_server.url}]
    )
    stimuli = reverse("admin:studyplatform_study_stimuli", args=[fingerspelling.pk])
    progress = reverse("admin:studyplatform_study_stimuli_progress", args=[fingerspelling.pk])
    # Its nonce'd inline script polls the progress: its first poll is the event to wait on.
    # Matched by URL: the participant page's last fetch can still answer during the goto.
    with page.expect_response(lambda r: r.url.endswith(progress)) as polled:
        page.goto(live_server.url + stimuli)
    assert polled.value.ok and polled.value.json()["total"] >= 0
    page.wait_for_selector("#stimuli-bar")
    assert page.violations == []


def _session_of(user) -> str:
    from django.test import Client

    client = Client()
    client.force_login(user)
    return client.cookies["sessionid"].value
