"""Take studies through the participant views: flow, idempotent saves, tampering, isolation."""

import hashlib
import json
import re
from collections import Counter
from datetime import timedelta

import pytest
from django.urls import reverse
from django.utils import timezone

from studyplatform.actions import do_enroll_participant
from studyplatform.lib.schedule import build_schedule
from studyplatform.models import MediaEvent, Participant, PersonalAnswer, Response, Trial
from tests.conftest import tiny_webm, video_frames

pytestmark = pytest.mark.django_db


def _start(client, study, query=""):
    """Open the study link, agree, and return the participant it created."""
    url = reverse("study_welcome", args=[study.slug]) + query
    welcome = client.get(url)
    assert welcome.status_code == 200
    assert study.consent_text.split(".")[0] in welcome.text
    moved = client.post(url, {"consent": "yes"})
    participant = Participant.objects.latest("pk")
    assert moved["Location"] == reverse("participant_page", args=[participant.token, 1])
    return participant


def _answer_page(client, participant, number):
    """Post sensible answers to every question of page *number*; return the response."""
    participant.refresh_from_db()
    trial = Trial.objects.get(
        study=participant.study, key=participant.schedule[number - 1]["trial"]
    )
    data = {"nav": "next"}
    for question in trial.questions.all():
        if question.kind == "pairwise":
            data[f"q-{question.key}"] = "1"
        elif question.uses_options:
            data[f"q-{question.key}"] = str(question.options.order_by("value").last().value)
        elif question.kind == "number":
            data[f"q-{question.key}"] = "12"
        else:
            data[f"q-{question.key}"] = "" if question.is_personal else "Smooth motion."
    return client.post(reverse("participant_page", args=[participant.token, number]), data)


def _save(client, participant, **payload):
    return client.post(
        reverse("participant_answer", args=[participant.token]),
        json.dumps(payload),
        content_type="application/json",
    )


def test_a_participant_goes_from_link_to_completion_code(client, fingerspelling):
    participant = _start(client, fingerspelling, "?PROLIFIC_PID=abc123&STUDY_ID=s9")
    assert participant.recruitment_params == {"PROLIFIC_PID": "abc123", "STUDY_ID": "s9"}
    assert participant.consented_at is not None
    total = len(participant.schedule)
    assert total == fingerspelling.trials.count() == 53
    first = client.get(reverse("participant_page", args=[participant.token, 1]))
    assert f"Page 1 of {total}" in first.text
    for number in range(1, total + 1):
        response = _answer_page(client, participant, number)
        assert response.status_code == 302, (number, response.text[:2000])
    participant.refresh_from_db()
    assert participant.is_finished and participant.position == total + 1
    done = client.get(response["Location"])
    assert "FSPELL-DEMO" in done.text
    # 49 comparisons (48 + practice) + the attention check + 2 demographics + 5 open.
    assert Response.objects.filter(participant=participant).count() == 57
    assert not PersonalAnswer.objects.exists()  # the optional name/e-mail were left empty


def test_the_study_link_resumes_and_the_token_link_works_elsewhere(client, fingerspelling):
    participant = _start(client, fingerspelling)
    _answer_page(client, participant, 1)
    again = client.get(reverse("study_welcome", args=[fingerspelling.slug]))
    assert again["Location"] == reverse("participant_page", args=[participant.token, 2])
    from django.test import Client

    elsewhere = Client()  # another browser with the personal link
    resumed = elsewhere.get(reverse("participant_resume", args=[participant.token]))
    assert resumed["Location"] == reverse("participant_page", args=[participant.token, 2])
    assert Participant.objects.count() == 1


def test_a_repeated_next_changes_nothing(client, fingerspelling):
    participant = _start(client, fingerspelling)
    _answer_page(client, participant, 1)
    _answer_page(client, participant, 2)  # instructions
    before = list(Response.objects.values_list("pk", "revision"))
    for _ in range(3):  # double clicks and back-button re-posts of page 2
        repeated = _answer_page(client, participant, 2)
        assert repeated["Location"] == reverse("participant_page", args=[participant.token, 3])
    participant.refresh_from_db()
    assert participant.position == 3
    assert list(Response.objects.values_list("pk", "revision")) == before


def test_optional_is_said_once(client, fingerspelling):
    """Issue 20: "Your name (optional) (optional)"."""
    participant = _start(client, fingerspelling)
    shown = client.get(reverse("participant_page", args=[participant.token, 1]))
    assert shown.text.count("(optional)") == 2  # the name and the e-mail address


def test_the_browser_time_of_an_answer_is_kept_and_implausible_ones_ignored(client, fingerspelling):
    """Issue 35: the quality columns compare the answer's browser time with the clips'."""
    participant = _start(client, fingerspelling)
    page = {"page": 1, "trial": participant.schedule[0]["trial"]}
    given = 1_764_770_000_123
    _save(client, participant, **page, question="age", value="3", rt_ms=900, client_ms=given)
    assert Response.objects.get().answered_client_ms == given
    for value, kept in (
        ("abc", None),
        (-5, None),
        (10**16, None),
        (True, None),
        ("1764770000999", 1_764_770_000_999),
    ):
        rating = str(3 + (Response.objects.get().revision % 2))
        saved = _save(client, participant, **page, question="age", value=rating, client_ms=value)
        assert saved.status_code == 200
        assert Response.objects.get().answered_client_ms == kept


def test_every_page_shows_the_participants_own_link_to_come_back(client, fingerspelling):
    """Issue 35: participants were never shown their personal resume link."""
    participant = _start(client, fingerspelling)
    shown = client.get(reverse("participant_page", args=[participant.token, 1])).text
    link = reverse("participant_resume", args=[participant.token])
    assert f'<a href="{link}">http://testserver{link}</a>' in shown
    assert client.get(link).status_code == 302  # it takes them back to where they were


def test_a_blocks_first_page_names_the_block_once(client, fingerspelling):
    """Issue 35: "Practice" was both the block's heading and the page's."""
    participant = _start(client, fingerspelling)
    participant.reached = len(participant.schedule)
    participant.save()
    number = next(i for i, e in enumerate(participant.schedule, 1) if e["trial"] == "practice-1")
    shown = client.get(reverse("participant_page", args=[participant.token, number])).text
    assert re.findall(r"<h[12][^>]*>([^<]*)</h[12]>", shown).count("Practice") == 1
    assert '<h1 id="block-title">Practice</h1>' in shown


def test_answers_save_at_once_and_idempotently(client, fingerspelling):
    participant = _start(client, fingerspelling)
    page = {"page": 1, "trial": participant.schedule[0]["trial"]}
    for _ in range(2):
        saved = _save(client, participant, **page, question="age", value="3", rt_ms=1200)
        assert saved.status_code == 200 and saved.json()["revision"] == 1
    changed = _save(client, participant, **page, question="age", value="4", rt_ms=1500)
    assert changed.json()["revision"] == 2
    response = Response.objects.get()
    assert (response.rating, response.rt_ms) == (4, 1500)
    shown = client.get(reverse("participant_page", args=[participant.token, 1]))
    assert 'value="4" checked' in shown.text  # the page shows the saved answer


@pytest.mark.parametrize(
    ("payload", "message"),
    [
        ({"question": "age", "value": "9"}, "“9” is not a point of the scale of “age”"),
        ({"question": "age", "value": "x"}, "“x” is not an answer to “age”"),
        ({"question": "most-natural", "value": "1"}, "“most-natural” is not asked on this page"),
        ({"question": "age", "value": "3", "trial": "cmp-01"}, "belongs to another page"),
        ({"question": "age", "value": "3", "page": 5}, "You have not reached this page yet"),
        ({"question": "age", "value": "3", "page": 999}, "There is no page 999"),
    ],
)
def test_a_tampered_answer_is_rejected_and_changes_nothing(
    client, fingerspelling, payload, message
):
    participant = _start(client, fingerspelling)
    body = {"page": 1, "trial": participant.schedule[0]["trial"], **payload}
    rejected = _save(client, participant, **body)
    assert rejected.status_code == 400
    assert message in rejected.json()["error"]
    assert not Response.objects.exists()


@pytest.mark.parametrize(
    ("body", "message"),
    [
        ('"rt_ms": 1e400', "not in the expected form"),  # infinite once parsed
        ('"rt_ms": NaN', "not in the expected form"),
        ('"rt_ms": "1e999"', "The response time '1e999' is not a number of milliseconds"),
        ('"rt_ms": true', "The response time 'True' is not a number of milliseconds"),
        ('"rt_ms": 1' + "0" * 400, "integer too large to use"),  # beyond 64 bits and floats
        ('"rt_ms": 1' + "0" * 5000, "not in the expected form"),  # beyond Python's digits
        ('"rt_ms": "\u0663"', "is not a number of milliseconds"),  # an Arabic-Indic 3
        ('"value": "\\ud800"', "not in the expected form"),  # a lone surrogate
        ('"extra": ' + "[" * 100_000 + "]" * 100_000, "not in the expected form"),
        ('"extra": ' + "[" * 40 + "]" * 40, "not in the expected form"),
    ],
)
def test_a_crafted_answer_gets_a_message_and_changes_nothing(client, fingerspelling, body, message):
    """Regression (issue 19): each of these was a server error (500)."""
    participant = _start(client, fingerspelling)
    trial = participant.schedule[0]["trial"]
    fields = {"page": 1, "trial": trial, "question": "age", "value": "3"}
    raw = (
        "{"
        + ", ".join(
            [
                *(
                    f"{json.dumps(k)}: {json.dumps(v)}"
                    for k, v in fields.items()
                    if f'"{k}"' not in body
                ),
                body,
            ]
        )
        + "}"
    )
    rejected = client.post(
        reverse("participant_answer", args=[participant.token]),
        raw,
        content_type="application/json",
    )
    assert rejected.status_code == 400
    assert message in rejected.json()["error"]
    assert not Response.objects.exists()


@pytest.mark.parametrize(
    ("event", "message"),
    [
        ('{"kind": "page_shown", "page": 1, "client_time_ms": 1e20}', "out of range"),
        (
            '{"kind": "page_shown", "page": 1, "client_time_ms": 100000000000000000000}',
            "integer too large to use",
        ),
        (
            '{"kind": "play", "page": 1, "clip": 1, "media_time_s": -1e9, "client_time_ms": 1}',
            "out of range",
        ),
        ('{"kind": "page_shown", "page": 1, "client_time_ms": 1' + "0" * 400 + "}", "too large"),
        ('{"kind": "page_shown", "page": 1, "client_time_ms": 9007199254740993}', "out of range"),
        ('{"kind": "page_shown", "page": 1, "client_time_ms": Infinity}', "JSON with Infinity"),
    ],
)
def test_a_crafted_event_gets_a_message_and_logs_nothing(client, fingerspelling, event, message):
    """Regression (issue 19): non-finite and huge client times were server errors."""
    participant = _start(client, fingerspelling)
    url = reverse("participant_events", args=[participant.token])
    refused = client.post(url, '{"events": [' + event + "]}", content_type="application/json")
    assert refused.status_code == 400 and message in refused.json()["error"]
    assert not MediaEvent.objects.exists()


def test_a_tampered_choice_in_the_form_is_rejected(client, fingerspelling):
    participant = _start(client, fingerspelling)
    for number in (1, 2, 3):
        _answer_page(client, participant, number)
    participant.refresh_from_db()
    number = next(i for i, e in enumerate(participant.schedule, 1) if e["trial"].startswith("cmp-"))
    participant.position = participant.reached = number
    participant.save()
    url = reverse("participant_page", args=[participant.token, number])
    count = Response.objects.count()
    bad = client.post(url, {"nav": "next", "q-most-natural": "3"})
    assert bad.status_code == 400 and "“3” is not one of the clips on this page" in bad.text
    unanswered = client.post(url, {"nav": "next"}, HTTP_ACCEPT="application/json")
    assert unanswered.status_code == 400
    assert unanswered.json()["questions"] == {"most-natural": "Please answer this question."}
    participant.refresh_from_db()
    assert participant.position == number and Response.objects.count() == count


def test_a_wrong_token_is_refused(client, fingerspelling):
    _start(client, fingerspelling)
    assert client.get(reverse("participant_resume", args=["nope"])).status_code == 404
    refused = _save(client, Participant(token="nope"), page=1, trial="x", question="age", value=1)
    assert refused.status_code == 404 and refused.json()["error"] == "This link is not valid."
    assert not Response.objects.exists()


def test_participants_never_share_a_session_or_see_each_other(client, fingerspelling):
    from django.test import Client

    first = _start(client, fingerspelling)
    other_client = Client()
    second = _start(other_client, fingerspelling)
    assert first.token != second.token
    _save(client, first, page=1, trial=first.schedule[0]["trial"], question="age", value="5")
    page = other_client.get(reverse("participant_page", args=[second.token, 1]))
    assert 'value="5" checked' not in page.text
    # A participant's pages show only their own answers, whoever asks.
    mine = other_client.get(reverse("participant_page", args=[first.token, 1]))
    assert 'value="5" checked' in mine.text
    assert Response.objects.get().participant == first


def test_explicit_consent_needs_the_box(client, fingerspelling):
    fingerspelling.consent_mode = "explicit"
    fingerspelling.save()
    url = reverse("study_welcome", args=[fingerspelling.slug])
    refused = client.post(url, {})
    assert refused.status_code == 400 and "Please tick the box" in refused.text
    assert not Participant.objects.exists()
    assert client.post(url, {"consent": "yes"}).status_code == 302


def test_a_closed_study_takes_no_one(client, fingerspelling):
    fingerspelling.status = "closed"
    fingerspelling.save()
    closed = client.get(reverse("study_welcome", args=[fingerspelling.slug]))
    assert closed.status_code == 410 and "not taking participants" in closed.text


def test_going_back_is_a_study_option(client, fingerspelling):
    participant = _start(client, fingerspelling)
    _answer_page(client, participant, 1)
    url = reverse("participant_page", args=[participant.token, 2])
    back = client.post(url, {"nav": "back"})
    assert back["Location"] == reverse("participant_page", args=[participant.token, 1])
    fingerspelling.allow_back = False
    fingerspelling.save()
    participant.refresh_from_db()
    _answer_page(client, participant, 1)
    earlier = client.get(reverse("participant_page", args=[participant.token, 1]))
    assert earlier["Location"] == url  # the earlier page is closed: back to the current one
    refused = _save(
        client,
        participant,
        page=1,
        trial=participant.schedule[0]["trial"],
        question="age",
        value="2",
    )
    assert "does not let you change answers" in refused.json()["error"]


def test_time_limit_and_one_sitting_close_the_session(client, fingerspelling):
    participant = _start(client, fingerspelling)
    url = reverse("participant_page", args=[participant.token, 1])
    Participant.objects.filter(pk=participant.pk).update(
        last_seen_at=timezone.now() - timedelta(hours=1)
    )
    assert "one sitting" in client.get(url).text  # the demo is a one-sitting study
    fingerspelling.one_sitting = False
    fingerspelling.time_limit_minutes = 30
    fingerspelling.save()
    Participant.objects.filter(pk=participant.pk).update(
        consented_at=timezone.now() - timedelta(minutes=31)
    )
    closed = client.get(url)
    assert closed.status_code == 410 and "time limit of 30 minutes has passed" in closed.text
    refused = _save(
        client,
        participant,
        page=1,
        trial=participant.schedule[0]["trial"],
        question="age",
        value="2",
    )
    assert "time limit" in refused.json()["error"] and not Response.objects.exists()


def test_a_time_limited_study_shows_the_time_left(client, fingerspelling):
    participant = _start(client, fingerspelling)
    url = reverse("participant_page", args=[participant.token, 1])
    assert 'role="timer"' not in client.get(url).text  # the demo has no time limit
    fingerspelling.time_limit_minutes = 20
    fingerspelling.save()
    page = client.get(url).text
    seconds = int(re.search(r'data-seconds-left="(\d+)"', page).group(1))
    assert 1190 <= seconds <= 1200 and "19 minutes left" in page and "time-low" not in page
    Participant.objects.filter(pk=participant.pk).update(
        consented_at=timezone.now() - timedelta(minutes=16, seconds=30)
    )
    page = client.get(url).text
    assert "3 minutes left" in page and "time-low" in page  # under five minutes: prominent


def _finish(participant):
    Participant.objects.filter(pk=participant.pk).update(
        finished_at=timezone.now(), position=len(participant.schedule) + 1
    )


def test_on_a_shared_computer_the_study_link_starts_afresh_after_a_finish(client, fingerspelling):
    welcome = reverse("study_welcome", args=[fingerspelling.slug])
    first = _start(client, fingerspelling)
    _finish(first)
    done = reverse("participant_done", args=[first.token])
    assert client.get(welcome)["Location"] == done  # by default: back to the thank-you page
    assert "next participant" not in client.get(done).text

    fingerspelling.shared_computer = True
    fingerspelling.save()
    second = _start(client, fingerspelling)  # the welcome page again, and a new participant
    assert second.pk != first.pk and second.token != first.token
    moved = client.get(welcome)
    assert moved["Location"] == reverse("participant_page", args=[second.token, 1])  # unfinished
    _finish(second)
    page = client.get(reverse("participant_done", args=[second.token])).text
    assert f'id="next-participant" href="{welcome}"' in page
    third = _start(client, fingerspelling)
    assert third.pk not in (first.pk, second.pk)
    # The third walks away unfinished: ?new=1 clears the computer for the fourth.
    assert client.get(welcome)["Location"] == reverse("participant_page", args=[third.token, 1])
    fourth = _start(client, fingerspelling, "?new=1&PROLIFIC_PID=p4")
    assert fourth.pk != third.pk and fourth.recruitment_params == {"PROLIFIC_PID": "p4"}
    assert Participant.objects.filter(study=fingerspelling).count() == 4
    fingerspelling.shared_computer = False  # elsewhere ?new=1 changes nothing
    fingerspelling.save()
    resumed = client.get(welcome + "?new=1")
    assert resumed["Location"] == reverse("participant_page", args=[fourth.token, 1])


def test_the_completion_redirect_carries_the_recruitment_ids(client, fingerspelling):
    fingerspelling.redirect_url = "https://example.org/done?pid={PROLIFIC_PID}&x={MISSING}"
    fingerspelling.save()
    participant = _start(client, fingerspelling, "?PROLIFIC_PID=a%20b")
    Participant.objects.filter(pk=participant.pk).update(finished_at=timezone.now())
    done = client.get(reverse("participant_done", args=[participant.token]))
    assert 'href="https://example.org/done?pid=a%20b&amp;x="' in done.text


def test_media_events_are_logged_once(client, fingerspelling):
    participant = _start(client, fingerspelling)
    url = reverse("participant_events", args=[participant.token])
    events = [
        {"kind": "page_shown", "page": 1, "client_time_ms": 1000},
        {"kind": "play", "page": 1, "clip": 1, "media_time_s": 0.0, "client_time_ms": 1001},
    ]
    for expected in (2, 0):  # the same batch again (its answer was lost): nothing new
        logged = client.post(url, json.dumps({"events": events}), content_type="application/json")
        assert logged.json() == {"logged": expected}
    assert MediaEvent.objects.count() == 2
    bad = [{"kind": "rewind", "page": 1}]
    refused = client.post(url, json.dumps({"events": bad}), content_type="application/json")
    assert refused.status_code == 400 and "unknown kind “rewind”" in refused.json()["error"]
    ahead = [{"kind": "play", "page": 9, "clip": 1}]
    refused = client.post(url, json.dumps({"events": ahead}), content_type="application/json")
    assert "not reached this page" in refused.json()["error"]
    assert MediaEvent.objects.count() == 2


def test_language_switch(client, spine):
    participant = _start(client, spine)
    assert participant.language == "asl_en"
    url = reverse("participant_language", args=[participant.token])
    client.post(url, {"language": "en"})
    participant.refresh_from_db()
    assert participant.language == "en"
    assert client.post(url, {"language": "fr"}).status_code == 400
    # The switch returns to the page it was made on, not to the participant's position
    # (a page reached by Back); a page not reached yet is refused that way.
    participant.reached = 3
    participant.save()
    switched = client.post(url, {"language": "asl_en", "page": "2"})
    assert switched.url == reverse("participant_page", args=[participant.token, 2])
    ahead = client.post(url, {"language": "asl_en", "page": "9"})
    assert ahead.url == reverse("participant_page", args=[participant.token, 1])


def test_schedules_are_reproducible_from_the_seed(fingerspelling):
    participant = do_enroll_participant(fingerspelling)
    assert build_schedule(fingerspelling, participant.seed, 0) == participant.schedule
    keys = [entry["trial"] for entry in participant.schedule]
    assert keys[:3] == ["demographics", "instructions", "practice-1"] and keys[-1] == "closing"
    other = do_enroll_participant(fingerspelling)
    assert [e["trial"] for e in other.schedule] != keys  # the comparisons are shuffled
    swaps = [e["swap"] for e in participant.schedule if e["trial"].startswith("cmp-")]
    assert 10 < sum(swaps) < 38  # positions are randomized, about half swapped


def test_latin_square_rotation_balances_cells_over_participants(fingerspelling):
    fingerspelling.rotate_conditions = True
    fingerspelling.save()
    pairs, shown = Counter(), Counter()
    for _ in range(8):  # two rounds of the 4-row square
        participant = do_enroll_participant(fingerspelling)
        own = Counter()
        for entry in participant.schedule:
            if entry["trial"].startswith("cmp-"):
                trial = fingerspelling.trials.get(key=entry["trial"])
                pairs[(trial.item.key, frozenset((entry["a"], entry["b"])))] += 1
                shown.update([(trial.item.key, entry["a"], 1), (trial.item.key, entry["b"], 2)])
                own[frozenset((entry["a"], entry["b"]))] += 1
        assert set(own.values()) == {8}  # each participant still meets every pair 8 times
    # Over the rows, every word meets every pair, and every condition in each position,
    # equally often (in design order, before the participant's random swaps).
    assert len(pairs) == 8 * 6 and set(pairs.values()) == {8}
    assert len(shown) == 8 * 4 * 2 and set(shown.values()) == {12}


WEBM = tiny_webm()


TAKE = "0b7c6f2e-4a1d-4e8b-9c3f-5d2a1b0e9f81"


def _chunk(
    client,
    participant,
    number,
    data,
    offset,
    final=False,
    question="comments",
    take=TAKE,
    whole=None,
):
    """Send a chunk of take *take*; a final one says the SHA-256 of *whole* (default *data*)."""
    url = reverse("participant_signed_answer", args=[participant.token, number, question])
    headers = {
        "X-Upload-Take": take,
        "X-Upload-Offset": str(offset),
        "X-Upload-Final": "1" if final else "0",
    }
    if final:
        headers["X-Upload-Sha256"] = hashlib.sha256(data if whole is None else whole).hexdigest()
    return client.post(url, data, content_type="application/octet-stream", headers=headers)


def test_a_signed_answer_arrives_in_chunks_that_resume(client, at_comments):
    participant, number = at_comments
    first, rest = WEBM[:4000], WEBM[4000:]
    assert _chunk(client, participant, number, first, 0).json() == {"offset": 4000, "saved": False}
    # A chunk that does not start where the stored part ends: refused, with where to go on.
    again = _chunk(client, participant, number, first, 1)
    assert again.status_code == 409 and again.json()["offset"] == 4000
    url = reverse("participant_signed_answer", args=[participant.token, number, "comments"])
    url += f"?take={TAKE}"
    assert client.get(url).json() == {"offset": 4000}
    done = _chunk(client, participant, number, rest, 4000, final=True, whole=WEBM)
    assert done.json() == {"offset": len(WEBM), "saved": True}
    response = Response.objects.get(participant=participant)
    stored = response.video.read()
    assert response.text == "" and response.video_sha256 == hashlib.sha256(stored).hexdigest()
    # Stored remuxed: the same frames, now with a seek index (Matroska Cues).
    assert b"\x1c\x53\xbb\x6b" in stored and b"\x1c\x53\xbb\x6b" not in WEBM
    assert video_frames(stored) == video_frames(WEBM)
    assert client.get(url).json() == {"offset": 0}  # nothing left half-sent


def test_a_bad_signed_answer_is_refused(client, at_comments):
    participant, number = at_comments
    bad = _chunk(client, participant, number, b"<html>not a video</html>", 0, final=True)
    assert bad.status_code == 400 and "not a WebM or MP4 video" in bad.json()["error"]
    rating = next(i for i, e in enumerate(participant.schedule, 1) if e["trial"] == "rate-s1")
    refused = _chunk(client, participant, rating, WEBM, 0, final=True, question="clarity")
    assert "does not take a signed answer" in refused.json()["error"]
    other = _chunk(client, participant, rating, WEBM, 0, final=True)
    assert "not asked on this page" in other.json()["error"]
    no_offset = client.post(
        reverse("participant_signed_answer", args=[participant.token, number, "comments"]),
        WEBM,
        content_type="application/octet-stream",
    )
    assert "does not say where it starts" in no_offset.json()["error"]
    assert not Response.objects.exists()


def test_next_waits_for_every_clip_watched_to_the_end(client, fingerspelling):
    fingerspelling.require_full_view = True
    fingerspelling.save()
    participant = _start(client, fingerspelling)
    number = next(i for i, e in enumerate(participant.schedule, 1) if e["trial"] == "cmp-01")
    participant.reached = participant.position = number
    participant.save()
    url = reverse("participant_page", args=[participant.token, number])
    # Issue 20: with nothing answered (the questions wait for the clips), the reason given
    # was "Please answer every question".
    for form in ({"nav": "next"}, {"nav": "next", "q-most-natural": "1"}):
        refused = client.post(url, form)
        assert refused.status_code == 400 and "watch each clip to its end" in refused.text
    events = [
        {"kind": "ended", "page": number, "clip": clip, "client_time_ms": 5000 + clip}
        for clip in (1, 2)
    ]
    client.post(
        reverse("participant_events", args=[participant.token]),
        json.dumps({"events": events}),
        content_type="application/json",
    )
    assert client.post(url, {"nav": "next"}).status_code == 302


def test_no_participant_response_may_be_cached(client, fingerspelling):
    """Issue 19: participant pages lacked Cache-Control: no-store."""
    welcome = client.get(reverse("study_welcome", args=[fingerspelling.slug]))
    participant = _start(client, fingerspelling)
    responses = [
        welcome,
        client.get(reverse("participant_resume", args=[participant.token])),
        client.get(reverse("participant_page", args=[participant.token, 1])),
        _save(client, participant, trial="nope", question="nope", value="1"),
        client.post(
            reverse("participant_events", args=[participant.token]),
            "[]",
            content_type="application/json",
        ),
        client.get(reverse("participant_done", args=[participant.token])),
    ]
    for response in responses:
        assert "no-store" in response["Cache-Control"], response.request["PATH_INFO"]


def test_a_block_without_a_title_shows_no_name_of_its_own(client, fingerspelling):
    """Issue 55, item 7: participants read the builder's block name "Trials" as a heading
    (a block's key, shown when it had no title, is the data's name, not theirs)."""
    fingerspelling.blocks.filter(key="practice").update(title="", intro_text="Try one first.")
    participant = _start(client, fingerspelling)
    participant.reached = len(participant.schedule)
    participant.save()
    number = next(i for i, e in enumerate(participant.schedule, 1) if e["trial"] == "practice-1")
    shown = client.get(reverse("participant_page", args=[participant.token, number])).text
    headings = re.findall(r"<h[12][^>]*>([^<]*)</h[12]>", shown)
    assert "practice" not in headings and "Practice" not in headings, headings
    assert "Try one first." in shown  # the block's introduction is still there
