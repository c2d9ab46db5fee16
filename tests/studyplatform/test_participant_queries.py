"""Count the queries of a participant's requests: a page, an answer saved, and Next.

Issue 39: the participant's path is the platform's hottest; a query added to it costs
every participant on every page (bench/bench_load.py measures the time). The counts are
the most any page of the demo fingerspelling study takes, first visit and reload alike;
a change that adds a query fails here and must say why in the pinned figure.
"""

import json

import pytest
from django.db import connection
from django.test.utils import CaptureQueriesContext
from django.urls import reverse

from studyplatform.models import Trial
from tests.studyplatform.test_participate import _start

pytestmark = pytest.mark.django_db

# The most queries any page of the demo study takes, measured 2026-12-04 (the test
# client's transaction adds SAVEPOINT and RELEASE around each atomic block, counted here).
# A page: participant, trial, its questions, their options, the answers, the clips (6;
# 7 on the page with personal questions). A save: participant, trial, questions, the
# answer locked and written (9; 10 for a personal answer). Next: the page's reads, its
# answers locked once, the participant locked, the unanswered check and the move (12; 14
# on the first page, whose personal answers are written too). Before issue 39 Next took 27.
MAX_PAGE_QUERIES = 7
MAX_SAVE_QUERIES = 10
MAX_NEXT_QUERIES = 14


def _answers(trial: Trial) -> dict[str, str]:
    answers = {}
    for question in trial.questions.all():
        if question.kind == "pairwise":
            answers[question.key] = "1"
        elif question.uses_options:
            answers[question.key] = str(question.options.order_by("value").last().value)
        elif question.kind == "number":
            answers[question.key] = "30"
        elif question.kind == "email":
            answers[question.key] = "someone@example.org"
        else:
            answers[question.key] = "Smooth motion."
    return answers


def _count(send, *args, **kwargs) -> tuple[object, list[str]]:
    """Send a request with the test client; return its response and the SQL it ran."""
    with CaptureQueriesContext(connection) as queries:
        response = send(*args, **kwargs)
    return response, [query["sql"] for query in queries.captured_queries]


def _take_study(client, study) -> dict[str, list[list[str]]]:
    """Take every page of *study* as participate.js does; return each request's SQL."""
    participant = _start(client, study)
    sql: dict[str, list[list[str]]] = {"page": [], "reload": [], "save": [], "next": []}
    answer_url = reverse("participant_answer", args=[participant.token])
    for number, entry in enumerate(participant.schedule, 1):
        url = reverse("participant_page", args=[participant.token, number])
        for kind in ("page", "reload"):
            page, queries = _count(client.get, url)
            assert page.status_code == 200, page.content[:300]
            sql[kind].append(queries)
        trial = Trial.objects.get(study=study, key=entry["trial"])
        form = {"nav": "next"}
        for key, value in _answers(trial).items():
            body = {
                "page": number,
                "trial": trial.key,
                "question": key,
                "value": value,
                "rt_ms": 900,
            }
            saved, queries = _count(
                client.post,
                answer_url,
                json.dumps(body),
                content_type="application/json",
                HTTP_ACCEPT="application/json",
            )
            assert saved.status_code == 200, saved.content[:300]
            sql["save"].append(queries)
            form[f"q-{key}"] = value
        moved, queries = _count(client.post, url, form, HTTP_ACCEPT="application/json")
        assert moved.status_code == 200, moved.content[:300]
        sql["next"].append(queries)
    return sql


def test_a_participants_requests_take_a_fixed_few_queries(client, fingerspelling):
    sql = _take_study(client, fingerspelling)
    counts = {kind: [len(queries) for queries in requests] for kind, requests in sql.items()}
    print(json.dumps(counts))
    assert max(counts["page"] + counts["reload"]) <= MAX_PAGE_QUERIES, counts
    assert max(counts["save"]) <= MAX_SAVE_QUERIES, counts
    assert max(counts["next"]) <= MAX_NEXT_QUERIES, counts
