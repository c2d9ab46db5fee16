"""Withdrawal deletes a participant's data in one action, logged; retention expires it."""

import json
import os
from datetime import timedelta

import pytest
from django.core.management import call_command
from django.test import Client
from django.urls import reverse
from django.utils import timezone

from studyplatform.actions import do_apply_retention, do_withdraw_participant
from studyplatform.models import MediaEvent, Participant, PersonalAnswer, Response, Withdrawal
from tests.conftest import tiny_webm
from tests.studyplatform.test_participate import _chunk, _save, _start

pytestmark = pytest.mark.django_db(transaction=True)  # file deletion runs on commit


def _participant_with_everything(client, at_comments):
    """Give the at_comments participant a signed answer, a text answer and events."""
    participant, number = at_comments
    assert _chunk(client, participant, number, tiny_webm(), 0, final=True).json()["saved"]
    trial = participant.schedule[number - 1]["trial"]
    client.post(
        reverse("participant_events", args=[participant.token]),
        json.dumps({"events": [{"kind": "page_shown", "page": number, "client_time_ms": 1}]}),
        content_type="application/json",
    )
    video = Response.objects.get(participant=participant, trial__key=trial).video
    return participant, video


def test_a_withdrawal_deletes_everything_and_is_logged(client, at_comments, alice, fingerspelling):
    participant, video = _participant_with_everything(client, at_comments)
    path = video.path
    other = _start(client, fingerspelling)
    _save(client, other, page=1, trial=other.schedule[0]["trial"], question="name", value="Bo")
    withdrawal = do_withdraw_participant(participant, by=alice, reason="asked by e-mail")
    assert not Participant.objects.filter(pk=participant.pk).exists()
    assert not Response.objects.filter(participant_id=participant.pk).exists()
    assert not MediaEvent.objects.filter(participant_id=participant.pk).exists()
    assert not PersonalAnswer.objects.filter(participant_id=participant.pk).exists()
    assert not os.path.exists(path)  # the signed answer's video is gone from disk
    logged = Withdrawal.objects.get()
    assert logged == withdrawal and logged.participant_number == participant.pk
    assert (logged.responses, logged.events, logged.files, logged.withdrawn_by) == (1, 1, 1, alice)
    assert PersonalAnswer.objects.get(participant=other).value == "Bo"  # others untouched


def test_deleting_in_the_admin_is_a_withdrawal(client, at_comments, bob):
    participant, video = _participant_with_everything(client, at_comments)
    client.force_login(bob)  # the spine study's owner
    url = reverse("admin:studyplatform_participant_changelist")
    done = client.post(
        url, {"action": "delete_selected", "_selected_action": [participant.pk], "post": "yes"}
    )
    assert done.status_code == 302
    assert not Participant.objects.exists() and not video.storage.exists(video.name)
    assert Withdrawal.objects.get().withdrawn_by == bob
    listed = client.get(reverse("admin:studyplatform_withdrawal_changelist"))
    assert str(participant.pk) in listed.text


def test_retention_deletes_expired_personal_data_only(client, at_comments, fingerspelling):
    participant, video = _participant_with_everything(client, at_comments)
    study = participant.study
    study.personal_data_retention_days = 30
    study.save()
    Participant.objects.filter(pk=participant.pk).update(
        finished_at=timezone.now() - timedelta(days=31), recruitment_params={"PROLIFIC_PID": "x"}
    )
    recent = _start(Client(), study)
    Participant.objects.filter(pk=recent.pk).update(
        finished_at=timezone.now() - timedelta(days=1), recruitment_params={"PROLIFIC_PID": "y"}
    )
    result = do_apply_retention()
    assert (result.videos, result.recruitment_ids) == (1, 1)
    assert not video.storage.exists(video.name)
    answer = Response.objects.get(participant=participant)
    assert answer.video.name == ""  # the answer row stays, without its video
    assert Participant.objects.get(pk=participant.pk).recruitment_params == {}
    assert Participant.objects.get(pk=recent.pk).recruitment_params == {"PROLIFIC_PID": "y"}
    assert do_apply_retention().videos == 0  # nothing left to delete
    call_command("apply_retention")
