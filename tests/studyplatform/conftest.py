"""Fixtures of the platform's tests: the database in use, a participant at a signed
answer, a rendered clip."""

import os

import pytest

from tests.studyplatform.test_participate import _start


@pytest.fixture(autouse=True, scope="session")
def _expected_database(django_db_setup, django_db_blocker):
    """Fail at once when the PostgreSQL run has silently fallen back to SQLite."""
    from django.db import connection

    if os.environ.get("SIGNSTUDY_EXPECT_POSTGRES") and connection.vendor != "postgresql":
        pytest.exit(f"Expected PostgreSQL, but the suite runs on {connection.vendor}.", 1)


@pytest.fixture
def at_comments(client, spine, settings, tmp_path):
    """A spine participant who reached every page; the number of the signed-answer page."""
    settings.MEDIA_ROOT = tmp_path
    participant = _start(client, spine)
    participant.reached = len(participant.schedule)
    participant.save()
    number = next(i for i, e in enumerate(participant.schedule, 1) if e["trial"] == "comments")
    return participant, number


@pytest.fixture(scope="session")
def one_clip(renderable, tmp_path_factory):
    """Render one small real clip (the example word) once for the session."""
    from stimuli.clips import ClipSpec, render

    spec = ClipSpec(
        "word", "DOOR", {"timing": "constant"}, seed=1, width=96, height=72, rate_hz=20.0
    )
    return render(spec, tmp_path_factory.mktemp("clip"))


@pytest.fixture(scope="session")
def hd_clip(renderable, tmp_path_factory):
    """Render the example word at a new study's size, 1280 × 720, once for the session."""
    from stimuli.clips import ClipSpec, render

    spec = ClipSpec(
        "word", "DOOR", {"timing": "constant"}, seed=1, width=1280, height=720, rate_hz=10.0
    )
    return render(spec, tmp_path_factory.mktemp("hd-clip"))


@pytest.fixture
def clips_dir(one_clip, settings, tmp_path):
    settings.MEDIA_ROOT = tmp_path
    return tmp_path
