"""Load and faults: 200 participants at once through gunicorn on PostgreSQL, over loopback.

Target (issue 19): with realistic think time, p95 of a trial page, an answer save and Next
under 100 ms, 0 answers lost, 0 duplicated; with the application server killed in the
middle of the run (and restarted), PostgreSQL restarted, one worker killed (issue 33) or a
backup taken (issue 33), still 0 lost and 0 duplicated. --database sqlite runs the same
on the embedded database.

Each participant is a thread speaking HTTP to the server as the page's script does
(bench/participant_http.py: each answer saved at once and sent twice, as a retry of a lost
reply would, then Next; lost connections retried with backoff, server errors five times).
Participants start at random within --arrival-s seconds (a recruitment service fills a
study over minutes; --arrival-s 0 starts all at once); between pages each spends --think-s
seconds on average (uniform over half to one and a half times that; seed 000's
participants spent about 20 s a page); --think-s 0 is a stress test. Afterwards every
participant's stored answers are compared with what they sent: lost (sent, not stored),
duplicated or wrong (a revision above 1 or another value).
Prints figures; asserts nothing.

    .venv/bin/python bench/bench_load.py [--participants 200] [--pages 10] [--think-s 15]
        [--arrival-s 60] [--fault none|app-kill|worker-kill|backup|pg-restart]
        [--database postgres|sqlite] [--workers 3] [--threads 8]
"""

import argparse
import os
import statistics
import subprocess
import sys
import tempfile
import threading
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import machine
from app_server import AppServer
from participant_http import HttpParticipant, Refused

ROOT = Path(__file__).resolve().parent.parent
DATABASE = "signstudy_load"
POSTGRES = f"postgres://postgres@127.0.0.1:5432/{DATABASE}"
SLUG = "fingerspelling-timing"


def _percentile(values: list[float], share: float) -> float:
    ordered = sorted(values)
    return ordered[min(len(ordered) - 1, round(share * (len(ordered) - 1)))]


def _prepare(env: dict[str, str]) -> None:
    """Create the database afresh, migrate it, collect static files, load the demo studies."""
    if env["DATABASE_URL"] == POSTGRES:
        psql = ["psql", "-h", "127.0.0.1", "-U", "postgres", "-q", "-c"]
        subprocess.run([*psql, f"DROP DATABASE IF EXISTS {DATABASE}"], check=True)
        subprocess.run([*psql, f"CREATE DATABASE {DATABASE}"], check=True)
    for command in (["migrate", "--noinput"], ["collectstatic", "--noinput"], ["seed_demo"]):
        subprocess.run(
            [sys.executable, "manage.py", *command, "-v0"],
            cwd=ROOT,
            env=env,
            check=True,
            stdout=subprocess.DEVNULL,
        )


def _participant(url: str, number: int, pages: int, think_s: float, arrival_s: float):
    participant = HttpParticipant(url, patience_s=120, seed=number)
    time.sleep(arrival_s * participant.random.random())
    try:
        participant.enroll(SLUG)
        for page in range(1, pages + 1):
            if think_s:
                time.sleep(think_s * participant.random.uniform(0.5, 1.5))
            if not participant.take_page(page):
                break
    except Refused as error:
        return participant.answered, str(error)
    return participant.answered, ""


def _fault(kind: str, server: AppServer, at_s: float, log: list[str]) -> None:
    time.sleep(at_s)
    started = time.perf_counter()
    if kind == "app-kill":
        server.kill()
        time.sleep(2.0)
        server.start()
    elif kind == "worker-kill":
        log.append(f"worker {server.kill_worker()} killed (SIGKILL)")
    elif kind == "backup":
        archive = Path(server.env["SIGNSTUDY_VAR_DIR"]) / "under-load.tar.gz"
        subprocess.run(
            [sys.executable, "manage.py", "backup", str(archive)],
            cwd=ROOT,
            env=server.env,
            check=True,
            stdout=subprocess.DEVNULL,
        )
        log.append(f"backup of {archive.stat().st_size / 1e6:.1f} MB written")
    elif kind == "pg-restart":
        subprocess.run(["pg_ctlcluster", "15", "main", "restart"], check=True)
    log.append(f"{kind} at {at_s:.0f} s: back after {time.perf_counter() - started:.1f} s")


def _shown(row) -> str:
    """Return a stored response as the value the page's control sent."""
    if row.question.kind == "pairwise":
        return str(row.chosen_position)
    if row.number is not None:
        return f"{row.number:g}"
    return str(row.rating) if row.rating is not None else row.text


def _check(results) -> tuple[int, int, int]:
    """Return (stored, lost, duplicated-or-wrong) answers over all participants."""
    import django

    django.setup()
    from studyplatform.models import Participant, PersonalAnswer, Response

    stored = lost = wrong = 0
    for answered, _ in results:
        if not answered.token:
            continue
        participant = Participant.objects.get(token=answered.token)
        answers = Response.objects.filter(participant=participant)
        rows = {
            (r.trial.key, r.question.key): r for r in answers.select_related("trial", "question")
        }
        personal = dict(
            PersonalAnswer.objects.filter(participant=participant).values_list(
                "question__key", "value"
            )
        )
        for (trial, question), value in answered.sent.items():
            if question in personal:
                stored += 1
                wrong += personal[question] != value
                continue
            row = rows.pop((trial, question), None)
            if row is None:
                lost += 1
                continue
            stored += 1
            wrong += row.revision != 1 or _shown(row) != value
        wrong += len(rows)  # stored but never sent
    return stored, lost, wrong


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--participants", type=int, default=200)
    parser.add_argument("--pages", type=int, default=10)
    parser.add_argument("--think-s", type=float, default=15.0, help="mean seconds per page")
    parser.add_argument(
        "--arrival-s",
        type=float,
        default=60.0,
        help="participants start at random within this many seconds",
    )
    parser.add_argument(
        "--fault",
        default="none",
        choices=("none", "app-kill", "worker-kill", "backup", "pg-restart"),
    )
    parser.add_argument("--database", choices=("postgres", "sqlite"), default="postgres")
    parser.add_argument("--workers", type=int, default=3)
    parser.add_argument("--threads", type=int, default=8)
    args = parser.parse_args()
    print(machine.describe())
    with tempfile.TemporaryDirectory() as var_dir:
        kept = ("SIGNSTUDY_ACCESS_LOG",)
        env = {
            k: v
            for k, v in os.environ.items()
            if not k.startswith(("SIGNSTUDY_", "CELERY_")) or k in kept
        }
        database = POSTGRES if args.database == "postgres" else f"sqlite:///{var_dir}/load.sqlite3"
        env.update(
            SIGNSTUDY_VAR_DIR=var_dir,
            DATABASE_URL=database,
            DJANGO_SETTINGS_MODULE="studyplatform.settings",
        )
        try:
            _prepare(env)
        except (OSError, subprocess.CalledProcessError) as error:
            print(f"SKIPPED: no PostgreSQL on 127.0.0.1:5432 ({error})")
            return
        os.environ.update(env)
        server = AppServer(env, workers=args.workers, threads=args.threads)
        server.start()
        log: list[str] = []
        expected_s = args.arrival_s + args.think_s * args.pages or 20.0
        if args.fault != "none":
            threading.Thread(
                target=_fault, args=(args.fault, server, 0.4 * expected_s, log), daemon=True
            ).start()
        started = time.perf_counter()
        try:
            with ThreadPoolExecutor(args.participants) as pool:
                results = list(
                    pool.map(
                        lambda n: _participant(
                            server.url, n, args.pages, args.think_s, args.arrival_s
                        ),
                        range(args.participants),
                    )
                )
        finally:
            server.stop()
        wall = time.perf_counter() - started
        stored, lost, wrong = _check(results)
    timings = {
        kind: [t for answered, _ in results for t in answered.timings[kind]]
        for kind in ("page", "save", "next")
    }
    requests = sum(len(v) for v in timings.values())
    failed = [error for _, error in results if error]
    engine = "PostgreSQL" if args.database == "postgres" else "SQLite"
    print(
        f"{engine} through gunicorn ({args.workers} workers × {args.threads} threads): "
        f"{args.participants} participants arriving within {args.arrival_s:g} s × {args.pages} "
        f"pages, think time {args.think_s:g} s, fault {args.fault}; {requests} requests in "
        f"{wall:.1f} s "
        f"({requests / wall:.0f}/s), {sum(a.retries for a, _ in results)} retries"
    )
    for line in log:
        print(f"  {line}")
    for name, label in (("page", "trial page"), ("save", "answer save"), ("next", "Next")):
        values = [1000 * v for v in timings[name]]
        print(
            f"  {label:12s} median {statistics.median(values):6.1f} ms   "
            f"p95 {_percentile(values, 0.95):6.1f} ms   max {max(values):7.1f} ms  "
            f"(target p95 < 100 ms)"
        )
    print(
        f"  answers stored {stored}, lost {lost}, duplicated or wrong {wrong}; "
        f"participants who could not go on: {len(failed)}"
    )
    for error in sorted(set(failed))[:5]:
        print(f"    {error}")


if __name__ == "__main__":
    main()
