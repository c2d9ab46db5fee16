"""Test that a researcher cannot see or edit another researcher's study anywhere in the admin."""

import json

import pytest
from django.urls import reverse

from studyplatform.actions import Answer, do_enroll_participant, do_save_response
from studyplatform.models import Study
from tests.conftest import as_draft

pytestmark = pytest.mark.django_db


@pytest.fixture
def bob_client(client, bob):
    client.force_login(bob)
    return client


@pytest.fixture
def answered(fingerspelling):
    """Alice's study with one participant who answered one comparison."""
    participant = do_enroll_participant(fingerspelling)
    trial = fingerspelling.trials.get(key="cmp-01")
    do_save_response(participant, trial, trial.questions.get(), Answer(choice_position=1))
    return participant


def test_changelist_lists_only_own_studies(bob_client, fingerspelling, spine):
    page = bob_client.get(reverse("admin:studyplatform_study_changelist"))
    assert page.status_code == 200
    assert spine.title in page.text
    assert fingerspelling.title not in page.text


@pytest.mark.parametrize(
    "url_name",
    [
        "admin:studyplatform_study_change",
        "admin:studyplatform_study_delete",
        "admin:studyplatform_study_history",
        "admin:studyplatform_study_export",
        "admin:studyplatform_study_preview",
    ],
)
def test_urls_of_anothers_study_reveal_nothing(bob_client, fingerspelling, url_name):
    page = bob_client.get(reverse(url_name, args=[fingerspelling.pk]), follow=True)
    assert fingerspelling.title not in page.text
    assert "GUITAR" not in page.text
    assert page.status_code in (200, 404)
    if page.status_code == 200:  # the admin redirects to its index saying it does not exist
        assert "doesn’t exist" in page.text


def test_posting_to_anothers_study_changes_nothing(bob_client, fingerspelling):
    url = reverse("admin:studyplatform_study_change", args=[fingerspelling.pk])
    bob_client.post(url, {"title": "Hijacked", "slug": "hijacked", "status": "closed"})
    fingerspelling.refresh_from_db()
    assert fingerspelling.title == "ASL fingerspelling timing (demo)"


def test_actions_ignore_anothers_study(bob_client, fingerspelling, spine):
    url = reverse("admin:studyplatform_study_changelist")
    response = bob_client.post(
        url,
        {"action": "export_studies", "_selected_action": [fingerspelling.pk, spine.pk]},
    )
    assert response.status_code == 200
    assert json.loads(response.content)["study"]["slug"] == spine.slug
    bob_client.post(url, {"action": "duplicate_studies", "_selected_action": [fingerspelling.pk]})
    assert not Study.objects.filter(slug__startswith="fingerspelling-timing-copy").exists()


@pytest.mark.parametrize(
    "model, lookup",
    [
        ("trial", lambda s: s.trials.get(key="cmp-01")),
        ("question", lambda s: s.questions.get(key="age")),
        ("block", lambda s: s.blocks.get(key="comparisons")),
        ("answeroption", lambda s: s.questions.get(key="age").options.first()),
    ],
)
def test_design_objects_of_anothers_study_are_hidden(bob_client, fingerspelling, model, lookup):
    obj = lookup(fingerspelling)
    changelist = bob_client.get(reverse(f"admin:studyplatform_{model}_changelist"))
    assert f"/{obj.pk}/change/" not in changelist.text
    page = bob_client.get(
        reverse(f"admin:studyplatform_{model}_change", args=[obj.pk]), follow=True
    )
    assert "doesn’t exist" in page.text


def test_collected_data_of_anothers_study_is_hidden(bob_client, answered):
    for model in ("participant", "response"):
        changelist = bob_client.get(reverse(f"admin:studyplatform_{model}_changelist"))
        assert changelist.status_code == 200
        assert "0 " in changelist.text  # "0 participants" / "0 responses"
    page = bob_client.get(
        reverse("admin:studyplatform_participant_change", args=[answered.pk]), follow=True
    )
    assert answered.token not in page.text


def test_form_choices_offer_only_own_objects(bob_client, fingerspelling, spine):
    as_draft(spine)
    page = bob_client.get(reverse("admin:studyplatform_trial_add"))
    assert page.status_code == 200
    assert ">GUITAR</option>" not in page.text  # alice's item
    assert ">Motion capture (simulated)</option>" not in page.text
    assert ">S3</option>" in page.text  # bob's own item
    study_page = bob_client.get(reverse("admin:studyplatform_study_change", args=[spine.pk]))
    assert ">S3</option>" in study_page.text
    assert ">GUITAR</option>" not in study_page.text


def test_study_filter_lists_only_own_studies(bob_client, fingerspelling, spine):
    page = bob_client.get(reverse("admin:studyplatform_trial_changelist"))
    assert spine.title in page.text
    assert fingerspelling.title not in page.text


def test_new_study_belongs_to_its_creator(bob_client, bob, alice):
    page = bob_client.post(
        reverse("admin:studyplatform_study_add"),
        {
            "title": "Bob's new study",
            "slug": "bobs-new-study",
            "status": "draft",
            "owner": alice.pk,  # ignored: researchers cannot give studies away
            "consent_mode": "implicit",
            "allowed_devices": "any",
            "language": "en",
            "sign_language": "ASL",
            "manual_alphabet": "asl",
            "clip_width": 1280,
            "clip_height": 720,
            "thank_you_text": "Thanks",
            **{
                f"{prefix}-{field}": 0
                for prefix in (
                    "conditions",
                    "items",
                    "questions",
                    "blocks",
                    "trials",
                    "studyplatform-aslvideo-content_type-object_id",
                )
                for field in ("TOTAL_FORMS", "INITIAL_FORMS")
            },
        },
    )
    assert page.status_code == 302, page.text
    assert Study.objects.get(slug="bobs-new-study").owner == bob


def test_superuser_sees_every_study(admin_client, fingerspelling, spine):
    page = admin_client.get(reverse("admin:studyplatform_study_changelist"))
    assert fingerspelling.title in page.text and spine.title in page.text
    export = admin_client.get(reverse("admin:studyplatform_study_export", args=[fingerspelling.pk]))
    assert export.status_code == 200


def test_anonymous_users_are_sent_to_login(client, fingerspelling):
    export = client.get(reverse("admin:studyplatform_study_export", args=[fingerspelling.pk]))
    assert export.status_code == 302
    assert "/admin/login/" in export["Location"]
