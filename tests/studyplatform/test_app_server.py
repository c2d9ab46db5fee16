"""The application server `make demo` runs, serving a study, and killed in mid-save (issue 19).

gunicorn (deploy/gunicorn.conf.py) serves the test database (SQLite or PostgreSQL, the
run's own) from another process; participants talk to it over loopback HTTP with the
page script's retry rules (bench/participant_http.py).
"""

import os
import subprocess
import sys
import threading
import time
import urllib.request
from pathlib import Path

import pytest
from django.db import connection

from studyplatform.models import Participant, PersonalAnswer, Response

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "bench"))

from app_server import AppServer  # noqa: E402
from participant_http import HttpParticipant  # noqa: E402

# The server must see the rows.
pytestmark = [pytest.mark.django_db(transaction=True), pytest.mark.slow]


def _database_url() -> str:
    settings = connection.settings_dict
    if connection.vendor == "sqlite":
        return f"sqlite:///{settings['NAME']}"
    return (
        f"postgres://{settings['USER']}@{settings['HOST'] or '127.0.0.1'}:"
        f"{settings['PORT'] or 5432}/{settings['NAME']}"
    )


@pytest.fixture
def server(tmp_path):
    """gunicorn on a free port over this test's database, with collected static files."""
    env = {k: v for k, v in os.environ.items() if not k.startswith(("SIGNSTUDY_", "CELERY_"))}
    env.update(
        SIGNSTUDY_VAR_DIR=str(tmp_path),
        DATABASE_URL=_database_url(),
        SIGNSTUDY_MEDIA_ROOT=str(tmp_path / "media"),
    )
    subprocess.run(
        [sys.executable, "manage.py", "collectstatic", "--noinput", "-v0"],
        cwd=ROOT,
        env=env,
        check=True,
    )
    app = AppServer(env, workers=2, threads=4)
    app.media_root = tmp_path / "media"
    app.start()
    yield app
    app.stop()


def test_the_application_server_serves_the_study(server, fingerspelling):
    with urllib.request.urlopen(f"{server.url}/s/{fingerspelling.slug}/") as welcome:
        assert welcome.status == 200
        assert "gunicorn" in welcome.headers["Server"]
        assert "default-src 'self'" in welcome.headers["Content-Security-Policy"]
        assert "no-store" in welcome.headers["Cache-Control"]
        page = welcome.read().decode()
    static = page.split('href="/static/')[1].split('"')[0]  # WhiteNoise, hashed name
    with urllib.request.urlopen(f"{server.url}/static/{static}") as styles:
        assert styles.status == 200 and "immutable" in styles.headers["Cache-Control"]


def test_a_server_killed_in_mid_save_loses_and_duplicates_nothing(server, fingerspelling):
    participant = HttpParticipant(server.url, patience_s=60, seed=3)
    participant.enroll(fingerspelling.slug)
    pages, kills = 6, 0
    for number in range(1, pages + 1):
        done = threading.Event()
        worker = threading.Thread(
            target=lambda n=number, d=done: (participant.take_page(n), d.set())
        )
        sent = participant.answered.requests
        worker.start()
        # Kill in the middle of the page: after its first request (the page) and as the
        # next ones go out; waiting on progress, not on a clock, whatever the load.
        deadline = time.monotonic() + 10
        while participant.answered.requests < sent + 1 + number % 3 and not done.is_set():
            if time.monotonic() > deadline:
                break
            time.sleep(0.001)
        if not done.is_set():
            server.kill()
            kills += 1
            time.sleep(0.5)  # requests meanwhile find no server, and are retried
            server.start()
        worker.join(timeout=90)
        assert done.is_set(), f"page {number} never finished"
    assert kills >= 3 and participant.answered.retries > 0
    stored = Participant.objects.get(token=participant.answered.token)
    assert stored.position == pages + 1
    got = {(r.trial.key, r.question.key): r for r in Response.objects.filter(participant=stored)}
    personal = {a.question.key: a.value for a in PersonalAnswer.objects.filter(participant=stored)}
    for (trial, question), value in participant.answered.sent.items():
        if question in personal:
            assert personal[question] == value
            continue
        response = got.pop((trial, question))  # lost: KeyError
        assert response.revision == 1  # saved once, however often it was sent
    assert not got  # nothing stored that was not sent
