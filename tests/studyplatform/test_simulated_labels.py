"""Test that the demo's simulated conditions are labelled in every download.

The motion-capture condition is a simulated stand-in (marked so); Variable and
Normalized are timed by the built-in Variable model, trained on simulated holds, and
are labelled simulated from their parameters (issue 53, item 4).
"""

import io
import re
import zipfile

import pandas as pd
import pytest
from django.urls import reverse
from django.utils import timezone

from analysis import read_responses
from studyplatform.actions import Answer, do_enroll_participant, do_save_response
from studyplatform.lib.export import tidy_csv

pytestmark = pytest.mark.django_db
# The condition's label, as reports name it (its key, mocap, stays in the CSV).
NAME = "Motion capture"
LABEL = f"{NAME} (simulated)"
SIMULATED = ("mocap", "variable", "normalized")


@pytest.fixture
def answered(fingerspelling):
    """Four participants who answered every comparison of the fingerspelling demo."""
    assert fingerspelling.conditions.get(key="mocap").is_simulated
    for number in range(4):
        participant = do_enroll_participant(fingerspelling)
        for index, trial in enumerate(fingerspelling.trials.filter(key__startswith="cmp-")):
            answer = Answer(choice_position=1 + (index + number) % 2, rt_ms=900)
            do_save_response(participant, trial, trial.questions.get(), answer)
        participant.finished_at = timezone.now()
        participant.save()
    return fingerspelling


def test_the_csv_names_the_simulated_condition_on_each_row_that_shows_it(answered):
    frame = pd.read_csv(io.StringIO(tidy_csv(answered)), dtype=str, keep_default_na=False)
    shown = frame[["condition_a", "condition_b"]].to_numpy().tolist()
    expected = [";".join(k for k in dict.fromkeys(pair) if k in SIMULATED) for pair in shown]
    assert frame["condition_simulated"].tolist() == expected
    assert {"variable;mocap", "mocap", "variable"} <= set(expected)
    labels = set(read_responses(io.StringIO(tidy_csv(answered)))["condition_a"])
    assert {LABEL, "Variable (simulated)", "Normalized constant (simulated)"} <= labels
    assert "Constant" in labels and "Variable" not in labels


def test_a_condition_timed_by_the_built_in_model_says_what_it_was_trained_on(fingerspelling):
    variable = fingerspelling.conditions.get(key="variable")
    assert (
        not variable.is_simulated and variable.simulated and str(variable).endswith("(simulated)")
    )
    assert "384 holds simulated" in variable.description
    assert "leave-one-out 19.3 % exact, 16.6 ms per hold" in variable.description
    assert not fingerspelling.conditions.get(key="constant").simulated


def _without_methods(text: str) -> str:
    """Return a report file without its Method's account of how each condition was made
    (it quotes the timing technique, "Motion capture (the performance as performed)")."""
    text = re.sub(r'<dl class="methods">.*?</dl>', "", text, flags=re.S)
    return re.sub(r'"condition_methods": \{.*?\}', "", text, flags=re.S)


def test_the_results_page_and_every_report_file_say_simulated(answered, client, alice):
    client.force_login(alice)
    page = client.get(reverse("admin:studyplatform_study_results", args=[answered.pk])).text
    assert 'id="simulated-note"' in page and page.count(NAME) == page.count(LABEL)
    for name in ("results_report", "results_everything"):
        download = client.get(reverse(f"admin:studyplatform_study_{name}", args=[answered.pk]))
        archive = zipfile.ZipFile(io.BytesIO(download.content))
        checked = []
        for member in archive.namelist():
            if member.startswith("report/") and member.endswith(
                (".json", ".html", ".csv", ".tex", ".md")
            ):
                text = _without_methods(archive.read(member).decode())
                if NAME in text:
                    checked.append(member)
                    assert text.count(NAME) == text.count(LABEL), member
        assert {"report/report.html", "report/pairs.tex", "report/conditions.csv"} <= set(checked)
        # The Method says how each condition was made, the model's simulated training too.
        html = archive.read("report/report.html").decode()
        methods = re.search(r'<dl class="methods">(.*?)</dl>', html, re.S).group(1)
        assert "<dt>Variable (simulated)</dt>" in methods and "384 holds simulated" in methods
        assert "Automated spine" not in methods  # only the techniques of the study's items
        if name == "results_everything":
            assert "condition_simulated" in archive.read("responses.csv").decode()
