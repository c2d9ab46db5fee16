"""A Turkish study's page in Chromium: participate.js speaks Turkish (issue 55, item 1).

The clip controls and save messages come from Django's JavaScript catalogue for the
study's language (``/jsi18n/tr/``); the English message ids must not show.
"""

import pytest
from playwright.sync_api import expect

from studyplatform.models import Study
from tests.studyplatform.test_participate_browser import _with_clips, goto_trial_page

pytestmark = pytest.mark.django_db(transaction=True)


def test_the_clip_controls_and_saves_speak_the_study_language(
    page, live_server, fingerspelling, clips_dir, one_clip
):
    Study.objects.filter(pk=fingerspelling.pk).update(language="tr", replay_limit=1)
    fingerspelling.refresh_from_db()
    _with_clips(fingerspelling, one_clip, clips_dir)
    goto_trial_page(page, live_server, fingerspelling, "cmp-01")
    page.wait_for_selector("#page-form.ready")
    assert page.evaluate("document.documentElement.lang") == "tr"
    assert page.evaluate("typeof window.gettext") == "function"
    page.get_by_role("button", name="Klip 1 oynat").click()
    page.wait_for_function("document.querySelector('video.stimulus').ended")
    expect(page.get_by_role("button", name="Oynatma hakkı kalmadı")).to_be_visible()
    expect(page.get_by_text("1 oynatmadan 0 kaldı").first).to_be_visible()
    page.locator('input[name="q-most-natural"][value="1"]').check()
    expect(page.locator("#save-status")).to_have_text("Yanıt kaydedildi.")
    assert page.get_by_text("Play Clip").count() == 0
