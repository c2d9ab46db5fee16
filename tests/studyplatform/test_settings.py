"""Test that settings come from the environment with safe defaults."""

import os
import subprocess
import sys
from pathlib import Path

import pytest
from django.db import connection

ROOT = Path(__file__).resolve().parents[2]


def _settings_in_subprocess(env: dict[str, str], expression: str) -> str:
    code = (
        "import django, os\n"
        "os.environ['DJANGO_SETTINGS_MODULE'] = 'studyplatform.settings'\n"
        "from django.conf import settings\n"
        f"print({expression})\n"
    )
    clean_env = {
        k: v for k, v in os.environ.items() if not k.startswith(("SIGNSTUDY_", "DATABASE_URL"))
    }
    result = subprocess.run(
        [sys.executable, "-c", code],
        cwd=ROOT,
        env={**clean_env, **env},
        capture_output=True,
        text=True,
        check=True,
    )
    return result.stdout.strip()


def test_defaults_are_safe(tmp_path):
    env = {"SIGNSTUDY_VAR_DIR": str(tmp_path)}
    assert _settings_in_subprocess(env, "settings.DEBUG") == "False"
    assert _settings_in_subprocess(env, "settings.DATABASES['default']['ENGINE']") == (
        "django.db.backends.sqlite3"
    )


def test_secret_key_is_generated_once_and_kept(tmp_path):
    env = {"SIGNSTUDY_VAR_DIR": str(tmp_path)}
    first = _settings_in_subprocess(env, "settings.SECRET_KEY")
    second = _settings_in_subprocess(env, "settings.SECRET_KEY")
    assert first == second and len(first) >= 50
    key_file = tmp_path / "secret_key"
    assert key_file.read_text() == first
    assert oct(key_file.stat().st_mode & 0o777) == "0o600"


def test_processes_starting_at_once_read_one_whole_key(tmp_path):
    """Two test workers starting on a fresh clone read the key file as it was being
    written, got an empty key and failed every request (found by parallel test runs)."""
    from concurrent.futures import ThreadPoolExecutor
    from threading import Barrier

    from studyplatform.settings import _load_or_create_secret_key

    for attempt in range(20):
        path = tmp_path / f"key{attempt}" / "secret_key"
        start = Barrier(8)

        def read(_, path=path, start=start):
            start.wait()
            return _load_or_create_secret_key(path)

        with ThreadPoolExecutor(8) as pool:
            keys = set(pool.map(read, range(8)))
        assert len(keys) == 1 and len(keys.pop()) >= 50
        assert [p.name for p in path.parent.iterdir()] == ["secret_key"]


def test_secret_key_file_is_never_committed():
    ignored = subprocess.run(["git", "check-ignore", "-q", "var/secret_key"], cwd=ROOT, check=False)
    if ignored.returncode == 128:
        pytest.skip("not a git checkout")
    assert ignored.returncode == 0


def test_database_url_selects_postgresql(tmp_path):
    env = {"SIGNSTUDY_VAR_DIR": str(tmp_path), "DATABASE_URL": "postgres://u@db.example:5433/x"}
    assert (
        _settings_in_subprocess(
            env, "settings.DATABASES['default']['ENGINE'], settings.DATABASES['default']['PORT']"
        )
        == "django.db.backends.postgresql 5433"
    )


def test_debug_on_when_asked(tmp_path):
    env = {"SIGNSTUDY_VAR_DIR": str(tmp_path), "SIGNSTUDY_DEBUG": "1"}
    assert _settings_in_subprocess(env, "settings.DEBUG") == "True"


@pytest.mark.django_db
def test_sqlite_runs_in_wal_mode():
    if connection.vendor != "sqlite":
        pytest.skip("WAL mode concerns SQLite only; this run uses " + connection.vendor)
    with connection.cursor() as cursor:
        cursor.execute("PRAGMA journal_mode")
        assert cursor.fetchone()[0] == "wal"


def test_without_a_broker_jobs_run_here_quietly(tmp_path):
    """No broker: a job runs in the calling process, with no warning about a missing
    AMQP host and no per-task log lines (the commands report their own progress)."""
    code = (
        "import django, os\n"
        "os.environ['DJANGO_SETTINGS_MODULE'] = 'studyplatform.settings'\n"
        "django.setup()\n"
        "from studyplatform.celery import app\n"
        "@app.task\n"
        "def add(a, b):\n"
        "    return a + b\n"
        "print(add.delay(2, 3).get())\n"
    )
    clean_env = {
        k: v
        for k, v in os.environ.items()
        if not k.startswith(("SIGNSTUDY_", "DATABASE_URL", "CELERY_", "REDIS_URL"))
    }
    result = subprocess.run(
        [sys.executable, "-c", code],
        cwd=ROOT,
        env={**clean_env, "SIGNSTUDY_VAR_DIR": str(tmp_path)},
        capture_output=True,
        text=True,
        check=True,
    )
    assert result.stdout.strip() == "5"
    assert result.stderr == ""
    broker = {"SIGNSTUDY_VAR_DIR": str(tmp_path), "CELERY_BROKER_URL": "redis://127.0.0.1:6379/9"}
    assert _settings_in_subprocess(broker, "settings.CELERY_TASK_ALWAYS_EAGER") == "False"


def test_the_researchers_language_is_a_setting(tmp_path):
    """SIGNSTUDY_LANGUAGE sets the researcher's pages' language; one the interface does
    not have stops the server at start, naming the setting."""
    env = {"SIGNSTUDY_VAR_DIR": str(tmp_path)}
    assert _settings_in_subprocess(env, "settings.LANGUAGE_CODE") == "en"
    german = {**env, "SIGNSTUDY_LANGUAGE": "de"}
    assert _settings_in_subprocess(german, "settings.LANGUAGE_CODE") == "de"
    refused = subprocess.run(
        [sys.executable, "manage.py", "check"],
        cwd=ROOT,
        env={**os.environ, **env, "SIGNSTUDY_LANGUAGE": "xx"},
        capture_output=True,
        text=True,
    )
    assert refused.returncode != 0
    assert "SIGNSTUDY_LANGUAGE='xx' is not one of the interface's languages" in refused.stderr
