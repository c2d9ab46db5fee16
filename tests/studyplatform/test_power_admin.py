"""The "Plan sample size" page simulates a pilot study's power (issue 21)."""

import pytest
from django.urls import reverse

from studyplatform.models import Study
from tests.studyplatform.test_results import take_spine_study

pytestmark = pytest.mark.django_db


@pytest.fixture
def bob_client(client, bob):
    client.force_login(bob)
    return client


def test_plan_page_simulates_power_from_the_pilot(bob_client, spine):
    spine.status = Study.Status.PILOT
    spine.save()
    take_spine_study(spine, participants=6)
    url = reverse("admin:studyplatform_study_plan", args=[spine.pk])
    change = bob_client.get(reverse("admin:studyplatform_study_change", args=[spine.pk]))
    assert url in change.text
    options = {"kind": "pairwise", "smallest": 6, "largest": 12}
    page = bob_client.get(url, {**options, "step": 6, "simulations": 10, "seed": 3})
    assert page.status_code == 200, page.text
    assert page.context["error"] is None, page.context["error"]
    assert page.context["form"].errors == {}, page.context["form"].errors
    assert "Simulated power" in page.text and "simulated" in page.text
    table = page.context["table"]
    assert [row["participants"] for row in table] == [6, 12]
    # Conditions are named by their labels, as in the report.
    assert "mixed: conditions" in table[0]
    assert "binomial: Spine on vs Spine off (control)" in table[0]
    assert page.context["curve"].effects["source"].startswith(f"{spine.slug} pilot")
    assert "data:image/png;base64," in page.text
    assert "<td>6</td>" in page.text and "<td>6.00</td>" not in page.text  # N is a count


def test_plan_page_refuses_a_pilot_too_small_to_estimate_participants(bob_client, spine):
    """Issue 35: a 1-participant pilot gave "N = 20 gives power 0.88" without a word."""
    spine.status = Study.Status.PILOT
    spine.save()
    take_spine_study(spine, participants=1)
    url = reverse("admin:studyplatform_study_plan", args=[spine.pk])
    options = {"kind": "pairwise", "smallest": 10, "largest": 20, "step": 10}
    page = bob_client.get(url, {**options, "simulations": 10, "seed": 1})
    assert page.context["curve"] is None
    assert "the pilot has 1 participant; planning from a pilot needs at least 5" in page.text


def test_plan_page_needs_a_pilot_and_names_bad_options(bob_client, spine):
    url = reverse("admin:studyplatform_study_plan", args=[spine.pk])
    page = bob_client.get(url, {"kind": "pairwise"})
    assert "status to Pilot first" in page.text
    spine.status = Study.Status.PILOT
    spine.save()
    page = bob_client.get(
        url,
        {"kind": "rating", "smallest": 20, "largest": 10, "step": 1, "simulations": 10, "seed": 1},
    )
    assert "“To N” must not be below “From N”." in page.text
    assert page.context["curve"] is None
    page = bob_client.get(
        url,
        {"kind": "pairwise", "smallest": 5, "largest": 10, "step": 5, "simulations": 10, "seed": 1},
    )
    assert "the pilot has no responses yet." in page.text


def test_other_researchers_cannot_plan_the_study(client, alice, spine):
    client.force_login(alice)
    page = client.get(reverse("admin:studyplatform_study_plan", args=[spine.pk]))
    assert page.status_code in (302, 403, 404)
