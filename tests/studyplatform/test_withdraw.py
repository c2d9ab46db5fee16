"""A participant stops and withdraws on their own (issue 55, item 5): every answer and
file goes, the Withdrawals list records it with no researcher, the link stops working,
and a page without confirmation deletes nothing."""

import pytest
from django.test import Client
from django.urls import reverse

from studyplatform.actions import Answer, do_save_response
from studyplatform.models import Participant, Response, Withdrawal
from studyplatform.views.withdraw import WITHDRAWN_BY_PARTICIPANT
from tests.studyplatform.test_participate import _start

pytestmark = pytest.mark.django_db


def test_a_participant_withdraws_from_a_page_and_their_answers_are_deleted(client, spine):
    participant = _start(client, spine)
    trial = spine.trials.filter(questions__isnull=False).first()
    question = trial.questions.first()
    do_save_response(participant, trial, question, Answer(rating=3, text="x", choice_position=1))
    answers = Response.objects.filter(participant=participant).count()
    page = client.get(reverse("participant_page", args=[participant.token, 1]))
    withdraw_url = reverse("participant_withdraw", args=[participant.token])
    assert f'href="{withdraw_url}"' in page.text
    asked = client.get(withdraw_url)
    assert asked.status_code == 200 and 'id="withdraw-confirm"' in asked.text
    assert Participant.objects.filter(pk=participant.pk).exists()  # asking deletes nothing
    done = client.post(withdraw_url)
    assert done.status_code == 200 and "Your answers have been deleted" in done.text
    assert not Participant.objects.filter(pk=participant.pk).exists()
    assert not Response.objects.filter(participant_id=participant.pk).exists()
    logged = Withdrawal.objects.get(participant_number=participant.pk)
    assert logged.withdrawn_by is None and logged.reason == WITHDRAWN_BY_PARTICIPANT
    assert logged.responses == answers
    # The link is dead; the study's own link starts afresh in this browser.
    assert client.get(reverse("participant_page", args=[participant.token, 1])).status_code == 404
    again = client.get(withdraw_url)
    assert again.status_code == 404 and "not valid" in again.text


def test_withdrawing_needs_the_pages_form_not_just_a_link(spine):
    participant = _start(Client(), spine)
    forged = Client(enforce_csrf_checks=True)
    refused = forged.post(reverse("participant_withdraw", args=[participant.token]))
    assert refused.status_code == 403
    assert Participant.objects.filter(pk=participant.pk).exists()


@pytest.mark.django_db(transaction=True)
def test_withdrawing_on_a_phone_in_chromium(page, live_server, fingerspelling, clips_dir, one_clip):
    """At 390 px: the link is on the page without widening it, the confirmation and the
    last page pass axe-core's serious and critical rules, and the answers are gone."""
    from studyplatform.actions import do_enroll_participant
    from tests.studyplatform.test_participate_browser import (
        _serious_violations,
        _wait_ready,
        _with_clips,
    )

    _with_clips(fingerspelling, one_clip, clips_dir)
    participant = do_enroll_participant(fingerspelling, consented=True)
    page.set_viewport_size({"width": 390, "height": 844})
    page.goto(f"{live_server.url}/p/{participant.token}/1/")
    _wait_ready(page)
    assert page.evaluate("document.documentElement.scrollWidth") <= 390
    page.locator("#withdraw-link").click()
    page.locator("#withdraw-confirm").wait_for()
    assert _serious_violations(page) == []
    page.locator("#withdraw-confirm").click()
    page.locator("#withdrawn-note").wait_for()
    assert _serious_violations(page) == []
    assert not Participant.objects.filter(pk=participant.pk).exists()
