"""Test enrolment: unguessable tokens, recruitment parameters kept, pilot flagged."""

import pytest
from django.core.exceptions import ValidationError

from studyplatform.actions import do_enroll_participant
from studyplatform.lib import clean_recruitment_params
from studyplatform.models import Study

pytestmark = pytest.mark.django_db


def test_tokens_and_seeds_are_random_and_unique(fingerspelling):
    participants = [do_enroll_participant(fingerspelling) for _ in range(20)]
    tokens = {p.token for p in participants}
    assert len(tokens) == 20
    assert all(len(token) >= 43 for token in tokens)  # 256 bits, URL-safe base64
    assert len({p.seed for p in participants}) == 20


def test_recruitment_parameters_are_kept(fingerspelling):
    participant = do_enroll_participant(
        fingerspelling,
        recruitment_params={"PROLIFIC_PID": "5f1a", "STUDY_ID": "abc", "SESSION_ID": "s9"},
    )
    participant.refresh_from_db()
    assert participant.recruitment_params == {
        "PROLIFIC_PID": "5f1a",
        "STUDY_ID": "abc",
        "SESSION_ID": "s9",
    }


def test_oversized_parameters_are_dropped():
    params = {"ok": "1", "huge": "x" * 5000, "": "empty name", **{f"p{i}": "v" for i in range(40)}}
    kept = clean_recruitment_params(params)
    assert "huge" not in kept and "" not in kept and kept["ok"] == "1"
    assert len(kept) == 20


def test_pilot_participants_are_flagged(fingerspelling):
    fingerspelling.status = Study.Status.PILOT
    assert do_enroll_participant(fingerspelling).is_pilot
    fingerspelling.status = Study.Status.OPEN
    assert not do_enroll_participant(fingerspelling).is_pilot


@pytest.mark.parametrize("status", [Study.Status.DRAFT, Study.Status.CLOSED])
def test_draft_and_closed_studies_take_nobody(fingerspelling, status):
    fingerspelling.status = status
    with pytest.raises(ValidationError, match="is not taking participants now"):
        do_enroll_participant(fingerspelling)


def test_language_follows_the_study(fingerspelling, spine):
    assert do_enroll_participant(spine).language == "asl_en"
    assert do_enroll_participant(fingerspelling).language == "en"


def test_a_participant_who_writes_in_is_found_by_link_code_or_prolific_id(
    client, alice, fingerspelling
):
    """Issue 55, item 5: the admin's participant list searches the link (or its token),
    the completion code and the recruitment parameters, within the researcher's studies."""
    from django.urls import reverse

    from studyplatform.models import Participant

    wanted = do_enroll_participant(fingerspelling, recruitment_params={"PROLIFIC_PID": "5f3ab9"})
    other = do_enroll_participant(fingerspelling, recruitment_params={"PROLIFIC_PID": "77c01d"})
    Participant.objects.filter(pk=wanted.pk).update(completion_code="FSPELL-8K2Q")
    client.force_login(alice)
    url = reverse("admin:studyplatform_participant_changelist")
    link = f"https://lab.example.org/p/{wanted.token}/?lang=en"
    for term in ("5f3ab9", "FSPELL-8K2Q", wanted.token, link):
        page = client.get(url, {"q": term})
        assert page.status_code == 200
        shown = [p.pk for p in page.context["cl"].result_list]
        assert shown == [wanted.pk], term
    assert other.pk in [p.pk for p in client.get(url, {"q": "77c01d"}).context["cl"].result_list]
