"""Test the tidy export of collected responses and the admin results page."""

import io
import json
import re
import zipfile

import pandas as pd
import pytest
from django.urls import reverse
from django.utils import timezone

from analysis import check_responses
from studyplatform.actions import Answer, do_enroll_participant, do_save_response
from studyplatform.lib.export import tidy_csv

pytestmark = pytest.mark.django_db

# Seed 003 Table 3 counts (control, spine) per sentence, scaled down to 6 participants.
PREFERS_SPINE = {"S1": 3, "S2": 5, "S3": 2, "S4": 6, "S5": 4}


def _answer(participant, trial_key, question_key, answer):
    trial = participant.study.trials.get(key=trial_key)
    do_save_response(participant, trial, trial.questions.get(key=question_key), answer)


def take_spine_study(study, participants=6, rate_off=False):
    """Have *participants* complete the spine demo: pre-test, ratings, preferences.

    The spine-on sentences are rated; with *rate_off* the spine-off ones too, a point
    lower (as Part 1 of the demo asks).
    """
    taken = []
    for number in range(participants):
        participant = do_enroll_participant(
            study, recruitment_params={"PROLIFIC_PID": f"p{number}"}, consented=True
        )
        participant.schedule = [{"trial": "prefer-s2", "swap": number % 2 == 1}]
        _answer(participant, "pretest", "hearing-status", Answer(rating=1 + number % 3))
        _answer(participant, "pretest", "years-asl", Answer(number=10 + number))
        for sentence in range(1, 6):
            for question in ("clarity", "grammaticality", "understandability", "naturalness"):
                _answer(
                    participant,
                    f"rate-s{sentence}",
                    question,
                    Answer(rating=1 + (number + sentence) % 5),
                )
                if rate_off:
                    rating = max(1, (number + sentence) % 5 + (number % 2))
                    _answer(participant, f"rate-s{sentence}-off", question, Answer(rating=rating))
            trial = study.trials.get(key=f"prefer-s{sentence}")
            spine_first = trial.condition_a.key == "spine-on"
            swapped = any(
                e.get("trial") == trial.key and e.get("swap") for e in participant.schedule
            )
            if swapped:
                spine_first = not spine_first
            wants_spine = number < PREFERS_SPINE[f"S{sentence}"]
            position = 1 if spine_first == wants_spine else 2
            _answer(
                participant, trial.key, "preferred", Answer(choice_position=position, rt_ms=1200)
            )
        participant.finished_at = timezone.now()
        participant.save()
        taken.append(participant)
    return taken


def test_export_is_valid_tidy_data(spine):
    take_spine_study(spine)
    frame = pd.read_csv(io.StringIO(tidy_csv(spine)), dtype=str, keep_default_na=False)
    table = check_responses(frame)
    assert len(table) == 6 * (5 * 4 + 5)  # demographics become columns, not rows
    assert {"hearing-status", "years-asl"} <= set(table.columns)
    assert set(table["hearing-status"]) == {"Deaf", "Hard of hearing", "Hearing"}
    # The CSV names conditions by key and label; the analysis by label, keys kept.
    assert set(frame["condition_a_label"]) >= {"Spine on", "Spine off (control)"}
    assert set(frame["condition_a"]) >= {"spine-on", "spine-off"}
    preferences = table[table["kind"] == "pairwise"]
    spine_wins = preferences.groupby("item")["chosen"].apply(lambda c: (c == "Spine on").sum())
    assert spine_wins.to_dict() == PREFERS_SPINE
    # The swapped schedule shows Clip 1/Clip 2 as the participant saw them.
    swapped = preferences[
        (preferences["trial"] == "prefer-s2")
        & (preferences["participant"] == str(spine.participants.order_by("pk")[1].pk))
    ].iloc[0]
    trial = spine.trials.get(key="prefer-s2")
    assert (swapped["condition_a_key"], swapped["condition_b_key"]) == (
        trial.condition_b.key,
        trial.condition_a.key,
    )
    assert swapped["condition_a"] == trial.condition_b.label
    assert set(table["flags"]) == {""}


def test_flags_mark_pilot_incomplete_and_attention_failures(spine):
    participant = take_spine_study(spine, participants=1)[0]
    participant.is_pilot = True
    participant.finished_at = None
    participant.save()
    trial = spine.trials.get(key="prefer-s1")
    trial.is_attention_check = True
    trial.expected_answer = "spine-off"
    trial.save()
    frame = pd.read_csv(io.StringIO(tidy_csv(spine)), dtype=str, keep_default_na=False)
    flags = set(";".join(frame["flags"]).split(";"))
    assert {"pilot", "incomplete", "attention_check"} <= flags
    chosen = frame[frame["trial"] == "prefer-s1"]["chosen"].iloc[0]
    assert ("attention_failed" in flags) == (chosen != "spine-off")


def test_personal_answers_are_never_exported(fingerspelling):
    participant = do_enroll_participant(fingerspelling)
    trial = fingerspelling.trials.get(key="demographics")
    do_save_response(
        participant, trial, trial.questions.get(key="email"), Answer(text="me@example.org")
    )
    do_save_response(participant, trial, trial.questions.get(key="age"), Answer(rating=2))
    comparison = fingerspelling.trials.get(key="cmp-01")
    do_save_response(participant, comparison, comparison.questions.get(), Answer(choice_position=1))
    text = tidy_csv(fingerspelling)
    assert "me@example.org" not in text and "email" not in text
    assert "26–35" in text


@pytest.fixture
def bob_client(client, bob):
    client.force_login(bob)
    return client


def test_results_page_shows_the_analysis(bob_client, spine):
    take_spine_study(spine)
    page = bob_client.get(reverse("admin:studyplatform_study_results", args=[spine.pk]))
    assert page.status_code == 200
    assert "6 of 6 participants analysed" in page.text
    assert "Pairwise preferences" in page.text and "Ratings" in page.text
    assert "data:image/png;base64," in page.text
    assert "Only participants whose hearing-status is" in page.text
    assert 'id="mixed-models"' in page.text and "Mixed-effects Bradley–Terry" in page.text
    assert "Conditions alike:" in page.text


def test_results_page_accounts_for_every_participant(bob_client, spine):
    """Issue 56, item 6: the participant flow counts from the participant records, so one
    who agreed and left before answering is counted as started, not finished."""
    take_spine_study(spine)
    do_enroll_participant(spine, consented=True)  # agreed, then answered nothing
    page = bob_client.get(reverse("admin:studyplatform_study_results", args=[spine.pk]))
    flow = page.context["results"]["participant_flow"]
    assert (flow["started"], flow["consented"], flow["finished"]) == (7, 7, 6)
    assert flow["source"] == "participant records" and flow["analysed"] == 6
    assert 'id="participant-flow"' in page.text
    assert "Of 7 participants who started, 7 consented and 6 finished" in page.text
    assert "participant_flow" in page.context["figures"]
    archive = zipfile.ZipFile(
        io.BytesIO(
            bob_client.get(
                reverse("admin:studyplatform_study_results_report", args=[spine.pk])
            ).content
        )
    )
    assert "report/participant_flow.png" in archive.namelist()
    assert "Of 7 participants who started" in archive.read("report/report.html").decode()


def test_results_page_shows_every_test_with_its_interval_and_apa(bob_client, spine):
    """Issue 35, point 8: the post-hoc CIs, APA lines and Wilcoxon tests, and each
    condition across items with paired tests, are on the page (not only in the JSON)."""
    take_spine_study(spine, rate_off=True)
    page = bob_client.get(reverse("admin:studyplatform_study_results", args=[spine.pk]))
    text = page.text
    data = page.context["results"]
    assert data["pairwise"]["posthoc"] and data["pairwise"]["wilcoxon"]
    for test in data["pairwise"]["posthoc"] + data["pairwise"]["wilcoxon"]:
        assert test["apa"].replace("<", "&lt;") in text
    assert 'id="posthoc"' in text and "mean a − b" in text and 'id="wilcoxon"' in text
    assert "d_z 95 % CI" in text
    # Issue 56, item 7: the Bradley–Terry strengths the README lists are on the page too.
    strengths = data["pairwise"]["bradley_terry"]
    assert 'id="bradley-terry"' in text or strengths["not_estimable"] in text
    assert "By condition, across items" in text and "Conditions compared across items" in text
    summaries = data["rating_conditions"]
    assert {s["condition"] for s in summaries} == {"Spine on", "Spine off (control)"}
    assert {s["measure"] for s in summaries} == {
        "clarity",
        "grammaticality",
        "understandability",
        "naturalness",
    }
    comparisons = data["rating_condition_comparisons"]
    assert len(comparisons) == 4 and all(c["nobs"] == 6 for c in comparisons)
    for comparison in comparisons:
        assert comparison["apa"].replace("<", "&lt;") in text
    # A statistic that was not computed prints "–" in a cell, never "None".
    assert not re.search(r"<td>None</td>|>None<", text)


def test_results_page_applies_exclusions_and_filters(bob_client, spine):
    taken = take_spine_study(spine)
    taken[0].is_pilot = True
    taken[0].save()
    url = reverse("admin:studyplatform_study_results", args=[spine.pk])
    assert "5 of 6 participants analysed" in bob_client.get(url).text
    kept = bob_client.get(url, {"applied": "1", "ties": "exclude", "correction": "holm"})
    assert "6 of 6 participants analysed" in kept.text  # pilot box unticked
    deaf_only = bob_client.get(
        url,
        {
            "applied": "1",
            "exclude_pilot": "on",
            "ties": "exclude",
            "correction": "holm",
            "only_hearing-status": ["Deaf"],
        },
    )
    assert "1 of 6 participants analysed" in deaf_only.text  # P0 is pilot, P3 deaf


def test_results_page_without_responses(bob_client, spine):
    page = bob_client.get(reverse("admin:studyplatform_study_results", args=[spine.pk]))
    assert page.status_code == 200 and "No responses yet" in page.text


def test_downloads(bob_client, spine):
    take_spine_study(spine)
    csv = bob_client.get(reverse("admin:studyplatform_study_results_csv", args=[spine.pk]))
    assert csv["Content-Disposition"] == 'attachment; filename="spine-motion-responses.csv"'
    report = bob_client.get(reverse("admin:studyplatform_study_results_report", args=[spine.pk]))
    names = zipfile.ZipFile(io.BytesIO(report.content)).namelist()
    assert "report/results.json" in names and "report/report.html" in names
    assert "report/ratings_boxplots.png" in names
    everything = bob_client.get(
        reverse("admin:studyplatform_study_results_everything", args=[spine.pk])
    )
    archive = zipfile.ZipFile(io.BytesIO(everything.content))
    assert {"responses.csv", "spine-motion.study.json"} <= set(archive.namelist())
    results = json.loads(archive.read("report/results.json"))
    assert results["exclusions"]["participants_included"] == 6
    # The Method says how each condition was made: which spine formula, seed's or variant
    # (issue 53, item 3), from the conditions' own technique settings.
    methods = results["design"]["condition_methods"]
    assert set(methods) == set(results["design"]["conditions"])
    on = next(text for text in methods.values() if "Automated spine motion: on" in text)
    assert "seed 003 as printed" in on
    assert "Automated spine motion: off" in " ".join(methods.values())
    html = archive.read("report/report.html").decode()
    assert "How each condition's clips were made" in html


@pytest.mark.parametrize(
    "url_name",
    [
        "admin:studyplatform_study_results",
        "admin:studyplatform_study_results_csv",
        "admin:studyplatform_study_results_report",
        "admin:studyplatform_study_results_everything",
    ],
)
def test_another_researchers_results_are_hidden(client, alice, spine, url_name):
    take_spine_study(spine, participants=1)
    client.force_login(alice)
    response = client.get(reverse(url_name, args=[spine.pk]))
    assert response.status_code == 404


def test_everything_holds_media_events_seeds_and_schedules(bob_client, spine):
    import csv as csv_module

    from studyplatform.actions import do_log_media_events

    taken = take_spine_study(spine, participants=2)
    number = 1
    trial = spine.trials.get(key=taken[0].schedule[number - 1]["trial"])
    taken[0].reached = len(taken[0].schedule)
    taken[0].save()
    do_log_media_events(
        taken[0],
        [
            {
                "kind": "page_shown",
                "page": number,
                "client_time_ms": 1_000,
                "detail": {"width": 800},
            },
            {"kind": "play", "page": number, "clip": None, "client_time_ms": 1_500},
        ],
    )
    everything = bob_client.get(
        reverse("admin:studyplatform_study_results_everything", args=[spine.pk])
    )
    archive = zipfile.ZipFile(io.BytesIO(everything.content))
    events = list(csv_module.DictReader(io.StringIO(archive.read("media_events.csv").decode())))
    who = str(taken[0].pk)
    assert [(e["participant"], e["trial"], e["kind"]) for e in events] == [
        (who, trial.key, "page_shown"),
        (who, trial.key, "play"),
    ]
    assert json.loads(events[0]["detail"]) == {"width": 800}
    rows = list(csv_module.DictReader(io.StringIO(archive.read("participants.csv").decode())))
    by_id = {row["participant"]: row for row in rows}
    for participant in taken:
        row = by_id[str(participant.pk)]
        assert int(row["seed"]) == participant.seed
        assert json.loads(row["schedule"]) == participant.schedule
        # Issue 35: the Prolific id, for approving and paying, was in no export.
        assert json.loads(row["recruitment"]) == participant.recruitment_params
