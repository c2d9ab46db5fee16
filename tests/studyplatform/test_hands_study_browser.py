"""Full, reduced and reconstructed hands rendered from the admin and taken in Chromium.

Issue 18's acceptance: the hand-dimensionality demo template (full hand, seed 002's
reduced DOFs, digits rebuilt from three markers by seed 000's LWR) is imported for a
researcher, generated from the study page, taken to completion, and the report counts
the typed words and the pairwise choices that were made.
"""

import csv
import io

import pytest

from analysis.intelligibility import word_accuracy
from studyplatform.actions import do_import_study
from studyplatform.demo import hands_study
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

TYPED = {"CAB": "cab"}


def _answer(slug: str):
    def answer(page, key: str, number: int):
        if page.locator('[name="q-asl-fluency"]').count():
            page.locator('input[name="q-asl-fluency"][value="1"]').check()
            return None
        if page.locator('[name="q-which-word"]').count():
            item = Trial.objects.get(study__slug=slug, key=key).item.key
            page.locator('[name="q-which-word"]').fill(TYPED[item])
            page.locator('[name="q-which-word"]').press("Tab")
            return TYPED[item]
        position = 1 if number % 2 else 2
        page.locator(f'input[name="q-more-natural"][value="{position}"]').check()
        return position

    return answer


def test_reduced_and_reconstructed_hands_render_from_the_admin_and_are_taken(
    page, browser, live_server, alice, settings, tmp_path, renderable
):
    settings.MEDIA_ROOT = tmp_path
    # One word, every pair of hands once: a shorter study to take and render.
    definition = without_trials(
        filmed_small(hands_study(), 96, 72), lambda t: t.get("item") == "HIKE"
    )
    study = do_import_study(definition, owner=alice, status="draft").study
    url = live_server.url
    sign_in_at(page, url, f"/admin/studyplatform/study/{study.pk}/change/")
    generate_and_open(page, url, study)
    ready = Stimulus.objects.filter(condition__study=study, status="ready")
    assert ready.count() == 3
    assert {s.condition.key for s in ready} == {"full", "reduced", "reconstructed"}

    participant, answers = take_study(browser, url, study.slug, _answer(study.slug))
    assert participant.is_finished
    archive = download_report(page, url, study)

    clicked = {k: v for k, v in answers.items() if isinstance(v, int)}
    wins: dict[tuple[str, str], dict[str, int]] = {}
    for key, position in clicked.items():
        trial = Trial.objects.get(study=study, key=key)
        shown = [c.label for c in presented_conditions(participant, trial)]  # as reported
        pair = tuple(sorted(shown))
        wins.setdefault(pair, dict.fromkeys(pair, 0))[shown[position - 1]] += 1
    pairs = list(csv.DictReader(io.StringIO(archive.read("report/pairs.csv").decode())))
    assert len(pairs) == 3
    for row in pairs:
        counted = wins[tuple(sorted((row["a"], row["b"])))]
        assert {row["a"]: int(row["a_wins"]), row["b"]: int(row["b_wins"])} == counted

    scores = list(csv.DictReader(io.StringIO(archive.read("report/intelligibility.csv").decode())))
    typed = {k: v for k, v in answers.items() if isinstance(v, str)}
    assert len(scores) == len(typed) == 1
    for key, text in typed.items():
        trial = Trial.objects.get(study=study, key=key)
        row = next(r for r in scores if r["item"] == trial.item.key)
        assert row["condition"] == presented_conditions(participant, trial)[0].label
        assert float(row["mean_accuracy"]) == pytest.approx(word_accuracy(text, trial.item.text))
