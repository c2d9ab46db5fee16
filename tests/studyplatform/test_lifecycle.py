"""Test a study's lifecycle: a locked design, new versions, review, target N, codes."""

import re

import pytest
from django.core.exceptions import ValidationError
from django.urls import reverse

from stimuli.plan import Design, DesignSpec
from studyplatform.actions import (
    Answer,
    do_advance_participant,
    do_create_study_version,
    do_enroll_participant,
    do_review_participants,
    do_save_response,
)
from studyplatform.actions.design import do_build_design
from studyplatform.actions.participants import CODE_ALPHABET
from studyplatform.lib.export import tidy_csv
from studyplatform.lib.participants import completion_url
from studyplatform.models import Condition, Participant, Study, Trial
from tests.studyplatform.test_design_builder import WORDS, fresh  # noqa: F401 (a fixture)

pytestmark = pytest.mark.django_db


@pytest.fixture
def opened(fresh):  # noqa: F811
    """The fresh study with a built design, open."""
    do_build_design(fresh, DesignSpec(Design.BALANCED_PAIRS, ("constant", "variable"), WORDS))
    fresh.refresh_from_db()
    fresh.status = Study.Status.OPEN
    fresh.save()
    return fresh


def take(study, number: int, finish: bool = True) -> Participant:
    """Enroll participant *number* and answer every page (to the end with *finish*)."""
    participant = do_enroll_participant(
        study, recruitment_params={"PROLIFIC_PID": f"p{number}"}, consented=True
    )
    pages = len(participant.schedule) if finish else 1
    for page in range(1, pages + 1):
        trial = Trial.objects.get(study=study, key=participant.schedule[page - 1]["trial"])
        for question in trial.questions.filter(required=True):
            do_save_response(participant, trial, question, Answer(choice_position=1))
        do_advance_participant(participant, page, trial)
    participant.refresh_from_db()
    return participant


def test_an_open_studys_design_is_locked_in_the_models_and_the_admin(opened, client, alice):
    condition = opened.conditions.get(key="variable")
    with pytest.raises(ValidationError, match="design is locked"):
        condition.full_clean()
    client.force_login(alice)
    url = reverse("admin:studyplatform_condition_change", args=[condition.pk])
    page = client.get(url)
    assert page.status_code == 200 and 'name="_save"' not in page.text  # read only
    assert client.post(url, {"key": "changed"}).status_code == 403
    study_page = client.get(reverse("admin:studyplatform_study_change", args=[opened.pk])).text
    assert 'id="design-locked-note"' in study_page and "Make a new version" in study_page
    assert 'name="conditions-0-key"' not in study_page  # the inlines show, unchangeable
    trial = Trial.objects.filter(study=opened).first()
    assert (
        client.post(
            reverse("admin:studyplatform_trial_delete", args=[trial.pk]), {"post": "yes"}
        ).status_code
        == 403
    )


def test_the_lock_follows_the_data_not_the_status(opened, client, alice):
    """Issue 35: a study a participant took stays locked when its status says draft."""
    take(opened, 1, finish=False)
    Study.objects.filter(pk=opened.pk).update(status=Study.Status.DRAFT)
    opened.refresh_from_db()
    assert opened.design_locked and opened.lock_reason == "1 participant has taken it"
    condition = opened.conditions.get(key="variable")
    with pytest.raises(ValidationError, match="taken by 1 participant: its design is locked"):
        condition.full_clean()
    client.force_login(alice)
    url = reverse("admin:studyplatform_condition_change", args=[condition.pk])
    assert client.post(url, {"key": "changed"}).status_code == 403
    change = reverse("admin:studyplatform_study_change", args=[opened.pk])
    assert 'id="design-locked-note"' in client.get(change).text


def test_pilot_participants_do_not_lock_a_draft(fresh, client, alice):  # noqa: F811
    do_build_design(fresh, DesignSpec(Design.BALANCED_PAIRS, ("constant", "variable"), WORDS))
    fresh.refresh_from_db()
    fresh.status = Study.Status.PILOT
    fresh.save()
    pilot = take(fresh, 1, finish=False)
    assert pilot.is_pilot
    fresh.status = Study.Status.DRAFT
    fresh.save()
    assert not fresh.design_locked
    fresh.conditions.get(key="variable").full_clean()


def test_a_draft_stays_editable(fresh, client, alice):  # noqa: F811
    fresh.conditions.get(key="variable").full_clean()
    client.force_login(alice)
    condition = fresh.conditions.get(key="variable")
    page = client.get(reverse("admin:studyplatform_condition_change", args=[condition.pk]))
    assert 'name="_save"' in page.text


def test_a_new_version_is_a_draft_copy_and_the_old_keeps_its_participants(opened, client, alice):
    participant = take(opened, 1)
    client.force_login(alice)
    response = client.post(reverse("admin:studyplatform_study_new_version", args=[opened.pk]))
    copy = Study.objects.get(previous_version=opened)
    assert response["Location"] == reverse("admin:studyplatform_study_change", args=[copy.pk])
    assert (copy.version, copy.status, copy.slug) == (2, "draft", "fresh-v2")
    assert copy.title == "Fresh study (version 2)"
    assert copy.trials.count() == opened.trials.count() and not copy.participants.exists()
    Condition(study=copy, key="third", label="Third").full_clean()  # editable
    assert participant.study == opened and participant.responses.exists()
    third = do_create_study_version(copy, owner=alice)
    assert (third.version, third.slug, third.title) == (3, "fresh-v3", "Fresh study (version 3)")


def test_unique_completion_codes_and_the_redirect_that_carries_them(opened, client):
    opened.completion_code = "FRESH"
    opened.unique_completion_codes = True
    opened.redirect_url = "https://example.org/done?cc={CODE}&pid={PROLIFIC_PID}"
    opened.save()
    first, second = take(opened, 1), take(opened, 2)
    for participant in (first, second):
        assert re.fullmatch(f"FRESH-[{CODE_ALPHABET}]{{8}}", participant.completion_code)
    assert first.completion_code != second.completion_code
    assert completion_url(first) == f"https://example.org/done?cc={first.completion_code}&pid=p1"
    page = client.get(reverse("participant_done", args=[first.token])).text
    assert first.completion_code in page
    assert '<meta http-equiv="refresh" content="8;url=https://example.org/done?cc=' in page


def test_the_study_closes_itself_at_its_target_and_rejects_do_not_count(opened):
    opened.target_n = 2
    opened.save()
    first = take(opened, 1)
    take(opened, 2, finish=False)  # still taking part when the study closes
    do_review_participants(opened, [first.pk], Participant.Review.REJECTED)
    take(opened, 3)
    opened.refresh_from_db()
    assert opened.status == "open"  # the rejected one does not count
    take(opened, 4)
    opened.refresh_from_db()
    assert opened.status == "closed"


def test_a_rejected_participant_is_flagged_excluded_and_listed_with_the_reason(
    opened, client, alice
):
    first, _second = take(opened, 1), take(opened, 2)
    client.force_login(alice)
    url = reverse("admin:studyplatform_study_participants", args=[opened.pk])
    response = client.post(url, {"participant": [first.pk], "review": "reject"})
    assert response.status_code == 302
    first.refresh_from_db()
    assert first.review == "rejected"
    rows = [line for line in tidy_csv(opened).splitlines()[1:]]
    assert all(("excluded" in row) == row.startswith(f"{first.pk},") for row in rows)
    page = client.get(url).text
    row = page[page.index(f'id="participant-{first.pk}"') :]
    row = row[: row.index("</tr>")]
    assert "Rejected" in row and "excluded" in row
    assert 'id="roster-summary">2 participants; <strong>1</strong>' in page
    # Issue 35: a finished participant reached every page, not one more ("16 of 15").
    total = len(first.schedule)
    assert first.reached > total and f"<td>{total} of {total}</td>" in row


def test_another_researcher_cannot_review_or_version(opened, client, bob):
    client.force_login(bob)
    url = reverse("admin:studyplatform_study_participants", args=[opened.pk])
    assert client.get(url).status_code == 404
    new_version = reverse("admin:studyplatform_study_new_version", args=[opened.pk])
    assert client.post(new_version).status_code == 404
    assert not Study.objects.filter(previous_version=opened).exists()


def test_the_lock_reads_the_participants_once_per_page(fresh, client, alice):  # noqa: F811
    """Every inline row asks whether the design is locked: one count, not one per row."""
    from django.db import connection
    from django.test.utils import CaptureQueriesContext

    client.force_login(alice)
    with CaptureQueriesContext(connection) as queries:
        client.get(reverse("admin:studyplatform_study_change", args=[fresh.pk]))
    counts = [q for q in queries.captured_queries if "is_pilot" in q["sql"] and "COUNT" in q["sql"]]
    assert len(counts) == 1
