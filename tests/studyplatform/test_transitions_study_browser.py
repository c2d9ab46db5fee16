"""The transition study of seed 001 §5.2.3, rendered from the admin and taken in Chromium.

Issue 17's end-to-end acceptance: the demo template (linear, simple Hermite,
data-driven Hermite and blended transitions on two sign pairs) is imported for a
researcher, its clips are generated from the study page, a participant takes it to
completion in Chromium (typing what is signed and judging every pair on the comparative
scale), and the report downloaded from the results page has the comparative-scale table
(mean preference per pair of models with its CI and signed-rank test) and the
intelligibility scores, which match what was typed and clicked.
"""

import csv
import io
import zipfile
from pathlib import Path

import pytest
from playwright.sync_api import expect

from analysis.intelligibility import word_accuracy
from studyplatform.actions import do_import_study
from studyplatform.demo import transitions_study
from studyplatform.lib import presented_conditions
from studyplatform.models import Participant, Stimulus, Trial
from tests.conftest import close_context

pytestmark = pytest.mark.django_db(transaction=True)

TYPED = {"P1": "where surprise", "P2": "search"}


def _small(definition: dict) -> dict:
    """Return the template filmed small, so its eight clips render in seconds."""
    for condition in definition["conditions"]:
        condition["parameters"].update(width=160, height=120, rate_hz=20.0)
    return definition


def _take(browser, url: str, slug: str) -> tuple[Participant, dict, dict]:
    """Take the study; return the participant, the rating per page and the typed answers."""
    context = browser.new_context(bypass_csp=True)
    ratings, typed = {}, {}
    try:
        page = context.new_page()
        page.goto(f"{url}/s/{slug}/")
        page.get_by_role("button", name="Continue (I agree to take part)").click()
        while True:
            page.wait_for_selector("#page-form.ready")
            form = page.locator("#page-form")
            number, key = int(form.get_attribute("data-page")), form.get_attribute("data-trial")
            if page.locator('[name="q-asl-fluency"]').count():
                page.locator('input[name="q-asl-fluency"][value="2"]').check()
            elif page.locator('[name="q-saying"]').count():
                item = Trial.objects.get(study__slug=slug, key=key).item.key
                page.locator('[name="q-saying"]').fill(TYPED[item])
                page.locator('[name="q-saying"]').press("Tab")
                typed[key] = TYPED[item]
            else:
                rating = 3 if key.startswith("attention") else 1 + number % 5
                page.locator(f'input[name="q-compare-transitions"][value="{rating}"]').check()
                ratings[key] = rating
            page.get_by_text("Answer saved.").wait_for()
            button = page.locator("#next-button")
            finishing = button.text_content().strip() == "Finish"
            button.click()
            if finishing:
                break
            page.wait_for_function(
                f"document.getElementById('page-form').dataset.page !== '{number}'"
            )
        page.get_by_text("Thank you", exact=True).wait_for()
    finally:
        close_context(context)
    participant = Participant.objects.filter(study__slug=slug).order_by("-pk").first()
    return participant, ratings, typed


def test_the_transition_study_renders_from_the_admin_is_taken_and_reported(
    page, browser, live_server, alice, settings, tmp_path, renderable
):
    settings.MEDIA_ROOT = tmp_path
    study = do_import_study(_small(transitions_study()), owner=alice, status="draft").study
    url = live_server.url
    page.goto(f"{url}/admin/login/?next=/admin/studyplatform/study/{study.pk}/change/")
    page.get_by_label("Username").fill("alice")
    page.get_by_label("Password").fill("pw-alice")
    page.get_by_role("button", name="Log in").click()
    expect(page.get_by_text("Inter-sign transitions: data-driven Hermite").first).to_be_visible()

    page.get_by_role("link", name="Generate stimuli").first.click()
    page.get_by_role("button", name="Generate stimuli").click()
    expect(page.locator("#stimuli-percent")).to_have_text("100", timeout=300_000)
    expect(page.locator("#stimuli-failed")).to_have_text("0")
    assert Stimulus.objects.filter(condition__study=study, status="ready").count() == 8

    page.goto(f"{url}/admin/studyplatform/study/{study.pk}/change/")
    page.locator("#id_status").select_option("open")
    page.get_by_role("button", name="Save and continue editing").click()
    expect(page.locator(".messagelist .success")).to_be_visible()
    participant, ratings, typed = _take(browser, url, study.slug)
    assert participant.is_finished and len(ratings) == 13 and len(typed) == 2

    page.goto(f"{url}/admin/studyplatform/study/{study.pk}/change/")
    page.locator(".object-tools").get_by_role("link", name="Results").click()
    expect(page.get_by_role("heading", name="Comparative scale")).to_be_visible()
    expect(page.get_by_role("heading", name="Intelligibility")).to_be_visible()
    with page.expect_download() as download:
        page.get_by_role("link", name="report (zip)").click()
    archive = zipfile.ZipFile(io.BytesIO(Path(download.value.path()).read_bytes()))

    # What the participant did, by pair of models: preference in points for the first.
    # The report names conditions by key, simulated ones so labelled, in alphabetical order.
    labels = {
        c.key: c.key + (" (simulated)" if c.is_simulated else "") for c in study.conditions.all()
    }
    order = sorted(labels.values())
    expected: dict[tuple[str, str], list[float]] = {}
    for key, rating in ratings.items():
        trial = Trial.objects.get(study=study, key=key)
        if trial.is_attention_check:
            continue
        first, second = (labels[c.key] for c in presented_conditions(participant, trial))
        a, b = sorted((first, second), key=order.index)
        expected.setdefault((a, b), []).append((3 - rating) * (1 if first == a else -1))
    rows = list(csv.DictReader(io.StringIO(archive.read("report/comparative.csv").decode())))
    assert len(rows) == 6
    for row in rows:
        points = expected[(row["a"], row["b"])]
        assert float(row["mean_preference_a"]) == pytest.approx(sum(points) / len(points))
        assert int(row["participants"]) == 1 and int(row["judgements"]) == len(points)
    assert any("(simulated)" in row["a"] + row["b"] for row in rows)

    scores = list(csv.DictReader(io.StringIO(archive.read("report/intelligibility.csv").decode())))
    assert len(scores) == 2
    for key, answer in typed.items():
        trial = Trial.objects.get(study=study, key=key)
        shown = labels[presented_conditions(participant, trial)[0].key]
        row = next(r for r in scores if r["item"] == trial.item.key)
        assert row["condition"] == shown
        assert float(row["mean_accuracy"]) == pytest.approx(word_accuracy(answer, trial.item.text))
