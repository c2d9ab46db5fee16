"""Crafted participant requests get a 4xx JSON message and change nothing (issue 19)."""

import json
from datetime import timedelta

import pytest
from django.urls import reverse
from django.utils import timezone

from studyplatform.actions.events import FINISHED_GRACE
from studyplatform.models import MediaEvent, Participant, PersonalAnswer, Response
from tests.conftest import tiny_webm
from tests.studyplatform.test_participate import _chunk, _save, _start

pytestmark = pytest.mark.django_db


def _first_page(participant) -> dict:
    return {"page": 1, "trial": participant.schedule[0]["trial"]}


@pytest.mark.parametrize(
    ("payload", "message"),
    [
        ({"page": True}, "not in the expected form"),  # a boolean is no page number
        ({"value": "\u0663"}, "is not an answer to “age”"),  # an Arabic-Indic 3
        ({"value": " 3"}, "is not an answer to “age”"),
        ({"value": "3_0"}, "is not an answer to “age”"),
        ({"value": True}, "is not text or a number"),
        ({"value": ["3"]}, "is not text or a number"),
        ({"question": "name", "value": "x" * 9000}, "longer than 300 characters"),
    ],
)
def test_a_lenient_reading_is_refused(client, fingerspelling, payload, message):
    participant = _start(client, fingerspelling)
    refused = _save(
        client,
        participant,
        **{**_first_page(participant), "question": "age", "value": "3", **payload},
    )
    assert refused.status_code == 400 and message in refused.json()["error"]
    assert not Response.objects.exists() and not PersonalAnswer.objects.exists()


def test_a_rating_as_a_json_number_is_taken(client, fingerspelling):
    participant = _start(client, fingerspelling)
    assert (
        _save(client, participant, **_first_page(participant), question="age", value=3).status_code
        == 200
    )
    assert Response.objects.get().rating == 3


def test_control_and_bidi_characters_are_stripped(client, fingerspelling):
    participant = _start(client, fingerspelling)
    text = "Ann\x00a \u202eevil\u202c\x1b[31m\tB\u2066x\u2069\nC"
    assert (
        _save(
            client, participant, **_first_page(participant), question="name", value=text
        ).status_code
        == 200
    )
    assert PersonalAnswer.objects.get().value == "Anna evil[31m\tBx\nC"


def test_json_must_be_sent_as_json(client, fingerspelling):
    participant = _start(client, fingerspelling)
    body = json.dumps({**_first_page(participant), "question": "age", "value": "3"})
    for url in (
        reverse("participant_answer", args=[participant.token]),
        reverse("participant_events", args=[participant.token]),
    ):
        refused = client.post(url, body, content_type="text/plain")
        assert refused.status_code == 415
        assert (
            "must be sent as JSON (application/json), not “text/plain”" in refused.json()["error"]
        )
    assert not Response.objects.exists()


def test_events_need_the_browser_time_that_deduplicates_them(client, fingerspelling):
    participant = _start(client, fingerspelling)
    url = reverse("participant_events", args=[participant.token])
    event = {"kind": "page_shown", "page": 1}
    refused = client.post(
        url, json.dumps({"events": [event, event]}), content_type="application/json"
    )
    assert refused.status_code == 400 and "has no client_time_ms" in refused.json()["error"]
    assert not MediaEvent.objects.exists()


def _finish(participant, ago: timedelta) -> None:
    participant.finished_at = timezone.now() - ago
    participant.save()


def test_a_finished_participant_changes_nothing(client, fingerspelling):
    participant = _start(client, fingerspelling)
    events_url = reverse("participant_events", args=[participant.token])
    event = {"events": [{"kind": "page_shown", "page": 1, "client_time_ms": 5}]}
    _finish(participant, ago=timedelta(seconds=10))
    # The last page's late batch (sent as the page unloads) is still taken …
    taken = client.post(events_url, json.dumps(event), content_type="application/json")
    assert taken.json() == {"logged": 1}
    _finish(participant, ago=FINISHED_GRACE + timedelta(seconds=1))
    later = {"events": [{"kind": "page_shown", "page": 1, "client_time_ms": 6}]}
    refused = client.post(events_url, json.dumps(later), content_type="application/json")
    assert refused.status_code == 400 and "finished" in refused.json()["error"]
    assert MediaEvent.objects.count() == 1
    language_url = reverse("participant_language", args=[participant.token])
    language = client.post(
        language_url, {"language": "asl_en"}, headers={"Accept": "application/json"}
    )
    assert language.status_code == 400 and "finished" in language.json()["error"]
    participant.refresh_from_db()
    assert participant.language == "en"  # fingerspelling is not ASL-first
    answer = _save(client, participant, **_first_page(participant), question="age", value="3")
    assert answer.status_code == 400 and "finished" in answer.json()["error"]
    assert not Response.objects.exists()


def test_a_finished_participant_sends_no_recording(client, at_comments):
    participant, number = at_comments
    _finish(participant, ago=timedelta(seconds=1))
    refused = _chunk(client, participant, number, tiny_webm(), 0, final=True)
    assert refused.status_code == 400 and "finished" in refused.json()["error"]
    assert not Response.objects.exists()


def test_a_video_header_followed_by_html_is_no_video(client, at_comments):
    participant, number = at_comments
    for fake in (
        tiny_webm()[:200] + b"<html><script>alert(1)</script></html>" * 50,
        b"\x00\x00\x00\x18ftypmp42" + b"<html>" * 500,
    ):
        refused = _chunk(client, participant, number, fake, 0, final=True)
        assert refused.status_code == 400
        assert "incomplete or does not play" in refused.json()["error"]
    assert not Response.objects.exists()


def test_a_recording_sent_as_text_is_refused(client, at_comments):
    participant, number = at_comments
    url = reverse("participant_signed_answer", args=[participant.token, number, "comments"])
    refused = client.post(
        url,
        tiny_webm(),
        content_type="text/html",
        headers={"X-Upload-Offset": "0", "X-Upload-Final": "1"},
    )
    assert refused.status_code == 415 and "application/octet-stream" in refused.json()["error"]


def test_size_and_path_errors_answer_in_json(client, fingerspelling, settings):
    participant = _start(client, fingerspelling)
    settings.DATA_UPLOAD_MAX_MEMORY_SIZE = 1000
    body = json.dumps({**_first_page(participant), "question": "name", "value": "x" * 2000})
    too_big = client.post(
        reverse("participant_answer", args=[participant.token]),
        body,
        content_type="application/json",
    )
    assert too_big.status_code == 413 and "larger than the server takes" in too_big.json()["error"]
    lost = client.get(f"/p/{participant.token}/nowhere/", headers={"Accept": "application/json"})
    assert lost.status_code == 404 and lost.json() == {"error": "There is nothing at this address."}
    assert not PersonalAnswer.objects.exists()
    assert Participant.objects.get().finished_at is None
