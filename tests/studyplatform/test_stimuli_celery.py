"""Render stimuli through a real Celery worker and Redis, and survive a killed worker.

Needs Redis on 127.0.0.1:6379 (database 13 is used and flushed); skipped with a loud
message where none answers, failed instead when SIGNSTUDY_REQUIRE_REDIS is set. The
worker is a separate process sharing the test database (SQLite's test database is a
file here; PostgreSQL's is a server), so the tests commit for real.
"""

import contextlib
import os
import signal
import subprocess
import sys
import time
from contextlib import contextmanager
from pathlib import Path

import pytest
from django.db import connection

from studyplatform.actions.stimuli import do_generate_stimuli
from studyplatform.models import Stimulus, Trial

pytestmark = [pytest.mark.django_db(transaction=True), pytest.mark.slow]
ROOT = Path(__file__).resolve().parents[2]
REDIS_URL = "redis://127.0.0.1:6379/13"


@pytest.fixture
def broker(settings, monkeypatch):
    """Point the Celery app at Redis for this test (the suite runs tasks eagerly)."""
    try:
        import redis

        client = redis.Redis.from_url(REDIS_URL, socket_connect_timeout=1)
        client.ping()
        client.flushdb()
    except Exception as error:  # no server, refused, timeout: all mean "no Redis here"
        message = f"CELERY WORKER TESTS SKIPPED: no Redis at 127.0.0.1:6379 ({error})."
        if os.environ.get("SIGNSTUDY_REQUIRE_REDIS"):
            pytest.fail(message)
        pytest.skip(message)
    from celery import Celery

    from studyplatform.celery import app

    # The suite's Celery app runs jobs eagerly and keeps the connections it made; jobs
    # go to Redis through a second app, by name, as any other client would send them.
    sender = Celery("test-sender", broker=REDIS_URL, set_as_current=False)
    monkeypatch.setattr(app, "send_task", sender.send_task)
    settings.CELERY_TASK_ALWAYS_EAGER = False
    yield sender
    sender.close()
    client.flushdb()


def _database_url() -> str:
    s = connection.settings_dict
    if s["ENGINE"].endswith("sqlite3"):
        return f"sqlite:///{s['NAME']}"
    credentials = s["USER"] + (f":{s['PASSWORD']}" if s["PASSWORD"] else "")
    return f"postgres://{credentials}@{s['HOST'] or '127.0.0.1'}:{s['PORT'] or 5432}/{s['NAME']}"


@contextmanager
def _worker(tmp_path: Path, media: Path, private: Path | None = None):
    """Run a prefork Celery worker (one child) against the test database and Redis."""
    environment = {
        **os.environ,
        "CELERY_BROKER_URL": REDIS_URL,
        "SIGNSTUDY_VAR_DIR": str(tmp_path),
        "DATABASE_URL": _database_url(),
        "SIGNSTUDY_MEDIA_ROOT": str(media),
        **({"SIGNSTUDY_PRIVATE_MEDIA_ROOT": str(private)} if private else {}),
    }
    log = open(tmp_path / "worker.log", "ab")  # noqa: SIM115 - closed below
    process = subprocess.Popen(
        [
            sys.executable,
            "-m",
            "celery",
            "-A",
            "studyplatform.celery",
            "worker",
            "--pool=prefork",
            "--concurrency=1",
            "--loglevel=INFO",
            "--without-gossip",
            "--without-mingle",
        ],
        cwd=ROOT,
        env=environment,
        stdout=log,
        stderr=subprocess.STDOUT,
        start_new_session=True,  # its own process group: the pool's child goes with it
    )
    try:
        yield process
    finally:
        process.terminate()
        try:
            process.wait(20)
        except subprocess.TimeoutExpired:
            process.kill()
            process.wait()
        # A child still rendering outlives its killed parent and would write into the
        # database after the test has flushed it.
        with contextlib.suppress(ProcessLookupError):
            os.killpg(process.pid, signal.SIGKILL)
        log.close()


def _wait_for(predicate, timeout_s: float, what: str, log: Path):
    deadline = time.monotonic() + timeout_s
    while time.monotonic() < deadline:
        if predicate():
            return
        time.sleep(0.3)
    pytest.fail(f"Timed out waiting for {what}. Worker log:\n{log.read_text()[-3000:]}")


@pytest.fixture
def one_clip_study(fingerspelling, settings, tmp_path):
    """The demo fingerspelling study cut to the clips of one page, rendered small."""
    settings.MEDIA_ROOT = tmp_path / "media"
    Trial.objects.filter(block__study=fingerspelling).exclude(key="cmp-01").delete()
    for condition in fingerspelling.conditions.all():
        condition.parameters = {**condition.parameters, "width": 96, "height": 72}
        condition.save()
    return fingerspelling


def _statuses(ids):
    return sorted(Stimulus.objects.filter(pk__in=ids).values_list("status", flat=True))


def test_a_real_worker_renders_a_small_study(broker, one_clip_study, tmp_path, renderable):
    with _worker(tmp_path, tmp_path / "media"):
        result = do_generate_stimuli(one_clip_study)
        assert result.queued == 2
        _wait_for(
            lambda: _statuses(result.stimulus_ids) == ["ready", "ready"],
            240,
            "both clips to be rendered",
            tmp_path / "worker.log",
        )
    for stimulus in Stimulus.objects.filter(pk__in=result.stimulus_ids):
        assert (tmp_path / "media" / stimulus.video.name).stat().st_size == stimulus.size_bytes


def test_a_worker_killed_mid_render_leaves_nothing_marked_done(
    broker, one_clip_study, tmp_path, renderable
):
    media = tmp_path / "media"
    with _worker(tmp_path, media) as worker:
        result = do_generate_stimuli(one_clip_study)
        log = tmp_path / "worker.log"
        _wait_for(
            lambda: "rendering" in _statuses(result.stimulus_ids),
            120,
            "a clip to start rendering",
            log,
        )
        children = subprocess.run(
            ["pgrep", "-P", str(worker.pid)], capture_output=True, text=True
        ).stdout.split()
        assert children, "the prefork worker has no child process"
        for child in children:
            os.kill(int(child), signal.SIGKILL)
        # Killed mid-render: the clip is not ready and no finished file carries its name.
        killed = Stimulus.objects.get(pk__in=result.stimulus_ids, status="rendering")
        assert not killed.video and not (media / "stimuli" / f"{killed.content_hash}.mp4").exists()
        # The job was not acknowledged: the worker hands it to a new child, which finishes.
        _wait_for(
            lambda: _statuses(result.stimulus_ids) == ["ready", "ready"],
            240,
            "the killed job to be redone",
            log,
        )
    assert "WorkerLostError" in log.read_text() or "lost" in log.read_text().lower()


def test_a_real_worker_converts_an_uploaded_clip(broker, spine, settings, tmp_path):
    """Issue 51: the upload's request only keeps the file; a worker converts it."""
    from studyplatform.actions.clip_uploads import do_queue_clip
    from studyplatform.models import ClipUpload, Condition, UploadedClip
    from tests.conftest import as_draft
    from tests.studyplatform.test_uploaded_clips import make_video, upload

    as_draft(spine)
    Condition.objects.filter(study=spine, key="spine-off").update(source="uploaded", parameters={})
    private = Path(settings.SIGNSTUDY_PRIVATE_MEDIA_ROOT)
    off = spine.conditions.get(key="spine-off")
    job = do_queue_clip(off, spine.items.get(key="S1"), upload(make_video(), "S1.mp4"))
    assert not UploadedClip.objects.exists()  # the request converted nothing
    with _worker(tmp_path, tmp_path / "media", private):
        done = lambda: ClipUpload.objects.get(pk=job.pk).status == "done"  # noqa: E731
        _wait_for(done, 120, "the clip to be converted", tmp_path / "worker.log")
    clip = UploadedClip.objects.get()
    assert (private / clip.video.name).stat().st_size == clip.size_bytes
