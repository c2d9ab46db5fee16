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

import pytest
from playwright.sync_api import expect

from analysis.intelligibility import word_accuracy
from studyplatform.actions import do_import_study
from studyplatform.demo import transitions_study
from studyplatform.lib import presented_conditions
from studyplatform.models import Stimulus, Trial
from tests.studyplatform.taking import (
    download_report,
    filmed_small,
    generate_and_open,
    sign_in_at,
    take_study,
    without_trials,
)

pytestmark = pytest.mark.django_db(transaction=True)

TYPED = {"P1": "where"}


def _answer(slug: str):
    """Answer as a participant who types what is signed and rates pairs 1–5 in turn."""

    def answer(page, key: str, number: int):
        if page.locator('[name="q-asl-fluency"]').count():
            page.locator('input[name="q-asl-fluency"][value="2"]').check()
            return None
        if page.locator('[name="q-saying"]').count():
            item = Trial.objects.get(study__slug=slug, key=key).item.key
            # Issue 35: what the signer said is one line, not a four-row box.
            assert page.locator('input[type="text"][name="q-saying"]').count() == 1
            page.locator('[name="q-saying"]').fill(TYPED[item])
            page.locator('[name="q-saying"]').press("Tab")
            return TYPED[item]
        rating = 3 if key.startswith("attention") else 1 + number % 5
        page.locator(f'input[name="q-compare-transitions"][value="{rating}"]').check()
        return rating

    return answer


def test_the_transition_study_renders_from_the_admin_is_taken_and_reported(
    page, browser, live_server, alice, settings, tmp_path, renderable
):
    settings.MEDIA_ROOT = tmp_path
    # One sign pair, every pair of models once: a shorter study to take and render.
    definition = without_trials(filmed_small(transitions_study()), lambda t: t.get("item") == "P2")
    study = do_import_study(definition, owner=alice, status="draft").study
    url = live_server.url
    sign_in_at(page, url, f"/admin/studyplatform/study/{study.pk}/change/")
    expect(page.get_by_text("Inter-sign transitions: data-driven Hermite").first).to_be_visible()
    generate_and_open(page, url, study)
    assert Stimulus.objects.filter(condition__study=study, status="ready").count() == 4
    participant, answers = take_study(browser, url, study.slug, _answer(study.slug))
    ratings = {k: v for k, v in answers.items() if isinstance(v, int)}
    typed = {k: v for k, v in answers.items() if isinstance(v, str)}
    comparisons = Trial.objects.filter(study=study, kind="comparative").count()
    assert participant.is_finished and len(ratings) == comparisons >= 6 and len(typed) == 1

    archive = download_report(page, url, study)
    expect(page.get_by_role("heading", name="Comparative scale")).to_be_visible()
    expect(page.get_by_role("heading", name="Intelligibility")).to_be_visible()

    # What the participant did, by pair of models: preference in points for the first.
    # The report names conditions by label, simulated ones so marked, in alphabetical order.
    labels = {
        c.key: c.label + (" (simulated)" if c.is_simulated else "") for c in study.conditions.all()
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
    assert len(scores) == 1
    for key, answer in typed.items():
        trial = Trial.objects.get(study=study, key=key)
        shown = labels[presented_conditions(participant, trial)[0].key]
        row = next(r for r in scores if r["item"] == trial.item.key)
        assert row["condition"] == shown
        assert float(row["mean_accuracy"]) == pytest.approx(word_accuracy(answer, trial.item.text))
