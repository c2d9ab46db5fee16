"""Time the participant pages with 50 simulated participants at once, on SQLite and PostgreSQL.

Target (issue 7): server time of a trial page and of a save at 50 concurrent participants,
p95 < 50 ms, with zero lost or duplicated responses after the run. Each participant is a
thread that takes the demo fingerspelling study through Django's request handler (no
network: the figure is the server's own time, database included): it opens the link,
agrees, then per page loads it, saves its answers at once (JSON, as the page's script
does, each sent twice as a retry would) and presses Next (twice on every fifth page, as a
double click). Between pages it spends --think-s seconds on average (uniform over half to
one and a half times that), as participants watch two clips and choose: seed 000's 51
pages took 15–20 minutes, about 20 s a page; the default 15 s is busier than that.
--think-s 0 is a stress test: the figures are then queueing time on the two cores.
Afterwards every participant's stored responses are compared with what they sent.
Prints figures; asserts nothing.

    .venv/bin/python bench/bench_participants.py [--participants 50] [--pages 10]
        [--think-s 15] [--database sqlite|postgres|both]
"""

import argparse
import json
import os
import random
import statistics
import subprocess
import sys
import tempfile
import threading
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import machine

ROOT = Path(__file__).resolve().parent.parent
POSTGRES = "postgres://postgres@127.0.0.1:5432/signstudy_bench"


def _percentile(values: list[float], share: float) -> float:
    ordered = sorted(values)
    return ordered[min(len(ordered) - 1, round(share * (len(ordered) - 1)))]


def _take_study(
    slug: str, pages: int, think_s: float, seed: int, timings: dict, lock: threading.Lock
) -> tuple[str, dict]:
    """Take *pages* pages of the study as one participant; return its token and answers."""
    from django.test import Client

    from studyplatform.models import Participant, Trial

    pause = random.Random(seed)
    time.sleep(think_s * pause.random())  # participants arrive over one page's time
    client = Client()
    client.post(f"/s/{slug}/", {"consent": "yes"})
    token = client.session["signstudy_participants"][slug]
    participant = Participant.objects.get(token=token)
    sent: dict = {}
    trials = {t.key: t for t in Trial.objects.filter(study=participant.study)}
    questions = {key: list(t.questions.all()) for key, t in trials.items()}
    mine = {"page": [], "save": [], "next": []}
    for number in range(1, pages + 1):
        if think_s:
            time.sleep(think_s * pause.uniform(0.5, 1.5))
        key = participant.schedule[number - 1]["trial"]
        started = time.perf_counter()
        shown = client.get(f"/p/{token}/{number}/")
        mine["page"].append(time.perf_counter() - started)
        assert shown.status_code == 200, (number, shown.status_code)
        for question in questions[key]:
            if question.is_personal:
                continue
            if question.kind == "pairwise":
                value = str(1 + (number + len(token)) % 2)
            elif question.uses_options:
                value = str(question.options.order_by("value").first().value)
            elif question.kind == "number":
                value = "30"
            else:
                value = f"open answer {number}"
            body = json.dumps(
                {
                    "page": number,
                    "trial": key,
                    "question": question.key,
                    "value": value,
                    "rt_ms": 900,
                }
            )
            for _ in range(2):  # the second is a retry of the first: changes nothing
                started = time.perf_counter()
                saved = client.post(f"/p/{token}/answer/", body, content_type="application/json")
                mine["save"].append(time.perf_counter() - started)
                assert saved.status_code == 200, saved.content
            sent[(key, question.key)] = value
        for _ in range(2 if number % 5 == 0 else 1):
            started = time.perf_counter()
            moved = client.post(f"/p/{token}/{number}/", {"nav": "next"})
            mine["next"].append(time.perf_counter() - started)
            assert moved.status_code == 302, moved.content
    with lock:
        for name, values in mine.items():
            timings[name].extend(values)
    return token, sent


def _check(results: list[tuple[str, dict]]) -> tuple[int, int, int]:
    """Return (stored, lost, wrong-or-extra) responses over all participants."""
    from studyplatform.models import Participant, Response

    stored = lost = wrong = 0
    for token, sent in results:
        participant = Participant.objects.get(token=token)
        rows = Response.objects.filter(participant=participant).select_related("trial", "question")
        got = {}
        for row in rows:
            question = row.question
            if question.kind == "pairwise":
                value = str(row.chosen_position)
            elif question.uses_options:
                value = str(row.rating)
            elif question.kind == "number":
                value = f"{row.number:g}"
            else:
                value = row.text
            got[(row.trial.key, question.key)] = value
        stored += len(got)
        lost += sum(1 for k in sent if k not in got)
        wrong += sum(1 for k, v in got.items() if sent.get(k) != v)
        wrong += sum(1 for row in rows if row.revision != 1)  # a retry counted as a change
    return stored, lost, wrong


def run(database: str, participants: int, pages: int, think_s: float) -> None:
    """Run the benchmark in this process against *database* (a fresh one)."""
    import django
    from django.core.management import call_command

    django.setup()
    from django.db import connections

    call_command("migrate", "--noinput", verbosity=0)
    call_command("collectstatic", "--noinput", verbosity=0)  # as a deployment serves them
    call_command("seed_demo", stdout=open(os.devnull, "w"))  # noqa: SIM115
    timings: dict = {"page": [], "save": [], "next": []}
    lock = threading.Lock()

    def participant(number):
        try:
            return _take_study("fingerspelling-timing", pages, think_s, number, timings, lock)
        finally:
            connections.close_all()

    started = time.perf_counter()
    with ThreadPoolExecutor(participants) as pool:
        results = list(pool.map(participant, range(participants)))
    wall = time.perf_counter() - started
    stored, lost, wrong = _check(results)
    requests = sum(len(v) for v in timings.values())
    print(
        f"{database}: {participants} participants × {pages} pages, think time {think_s:g} s, "
        f"{requests} requests in {wall:.1f} s ({requests / wall:.0f} requests/s)"
    )
    for name, label in (("page", "trial page"), ("save", "answer save"), ("next", "Next")):
        values = [1000 * v for v in timings[name]]
        print(
            f"  {label:12s} median {statistics.median(values):6.1f} ms   "
            f"p95 {_percentile(values, 0.95):6.1f} ms   max {max(values):7.1f} ms  "
            f"(target p95 < 50 ms)"
        )
    print(f"  responses stored {stored}, lost {lost}, duplicated or wrong {wrong}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--participants", type=int, default=50)
    parser.add_argument("--pages", type=int, default=10)
    parser.add_argument("--think-s", type=float, default=15.0, help="mean seconds per page")
    parser.add_argument("--database", choices=("sqlite", "postgres", "both"), default="both")
    parser.add_argument("--child", choices=("sqlite", "postgres"), help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.child:
        run(args.child, args.participants, args.pages, args.think_s)
        return
    print(machine.describe())
    for database in ("sqlite", "postgres") if args.database == "both" else (args.database,):
        with tempfile.TemporaryDirectory() as var_dir:
            unset = ("DATABASE_URL", "CELERY_BROKER_URL", "REDIS_URL")
            environment = {k: v for k, v in os.environ.items() if k not in unset}
            environment.update(
                SIGNSTUDY_VAR_DIR=var_dir,
                DJANGO_SETTINGS_MODULE="studyplatform.settings",
                SIGNSTUDY_ALLOWED_HOSTS="testserver",
            )
            if database == "postgres":
                drop = ["psql", "-h", "127.0.0.1", "-U", "postgres", "-q", "-c"]
                try:
                    subprocess.run([*drop, "DROP DATABASE IF EXISTS signstudy_bench"], check=True)
                    subprocess.run([*drop, "CREATE DATABASE signstudy_bench"], check=True)
                except (OSError, subprocess.CalledProcessError) as error:
                    print(f"postgres: SKIPPED, no server on 127.0.0.1:5432 ({error})")
                    continue
                environment["DATABASE_URL"] = POSTGRES
            command = [
                sys.executable,
                __file__,
                "--child",
                database,
                "--participants",
                str(args.participants),
                "--pages",
                str(args.pages),
                "--think-s",
                str(args.think_s),
            ]
            subprocess.run(command, check=True, env=environment, cwd=ROOT)


if __name__ == "__main__":
    main()
