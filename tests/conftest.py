"""Fixtures shared by the whole suite: researchers, studies, browsers, rendering.

Nothing here imports Django or the platform at import time, and nothing asks for a
database unless a test does: the engine's and the analysis's tests run without one
(tests/studyplatform/conftest.py checks which database the platform's tests use).
"""

import functools
import os
import re
import subprocess
import tempfile
import threading
import time
from contextlib import contextmanager
from pathlib import Path

import pytest


@functools.cache
def tiny_webm() -> bytes:
    """Return a real one-second WebM (VP8) a browser could have recorded, made by ffmpeg."""
    import imageio_ffmpeg

    command = [
        imageio_ffmpeg.get_ffmpeg_exe(),
        "-v",
        "error",
        "-f",
        "lavfi",
        "-i",
        "testsrc=size=160x120:rate=15",
        "-t",
        "1",
        "-c:v",
        "libvpx",
        "-b:v",
        "200k",
        "-f",
        "webm",
        "pipe:1",
    ]
    return subprocess.run(command, capture_output=True, check=True).stdout


def video_frames(video: bytes) -> list[bytes]:
    """Decode *video* (ffmpeg) and return its frames' pixels, to compare recordings."""
    import imageio_ffmpeg

    with tempfile.NamedTemporaryFile(suffix=".video") as handle:
        handle.write(video)
        handle.flush()
        frames = imageio_ffmpeg.read_frames(handle.name)
        next(frames)  # the metadata
        return list(frames)


@pytest.fixture
def make_researcher(django_user_model):
    """Return a factory of staff users in the Researchers group."""
    from django.contrib.auth.models import Group

    from studyplatform.signals import RESEARCHERS_GROUP

    def make(username: str):
        user = django_user_model.objects.create_user(username, password="pw-" + username)
        user.is_staff = True
        user.save()
        user.groups.add(Group.objects.get(name=RESEARCHERS_GROUP))
        return user

    return make


@pytest.fixture
def alice(make_researcher):
    return make_researcher("alice")


@pytest.fixture
def bob(make_researcher):
    return make_researcher("bob")


@pytest.fixture
def fingerspelling(alice):
    """The demo fingerspelling study, owned by alice."""
    from studyplatform.actions import do_import_study
    from studyplatform.demo import fingerspelling_timing_study

    return do_import_study(fingerspelling_timing_study(), owner=alice).study


@pytest.fixture
def spine(bob):
    """The demo spine study, owned by bob."""
    from studyplatform.actions import do_import_study
    from studyplatform.demo import spine_study

    return do_import_study(spine_study(), owner=bob).study


@pytest.fixture(autouse=True)
def _private_media_root(settings, tmp_path_factory):
    """Keep each test's personal files (signed answers, recordings) in a fresh directory."""
    settings.SIGNSTUDY_PRIVATE_MEDIA_ROOT = tmp_path_factory.mktemp("private")


@pytest.fixture(autouse=True)
def _withdrawal_ledger(settings, tmp_path_factory):
    """Give each test a withdrawal ledger of its own (a restore re-applies the ledger)."""
    settings.SIGNSTUDY_WITHDRAWAL_LEDGER = tmp_path_factory.mktemp("ledger") / "withdrawals.jsonl"


@pytest.fixture(autouse=True)
def _plain_static_storage(settings):
    """Serve static files without the collected manifest, which tests do not build."""
    settings.STORAGES = {
        **settings.STORAGES,
        "staticfiles": {"BACKEND": "django.contrib.staticfiles.storage.StaticFilesStorage"},
    }


@pytest.fixture(autouse=True)
def _fast_password_hashing(settings):
    """Hash test users' passwords cheaply; the real hasher takes ~0.3 s per user."""
    settings.PASSWORD_HASHERS = ["django.contrib.auth.hashers.MD5PasswordHasher"]


CHROMIUM = "/usr/bin/chromium"
# Flags for a sandboxed, offline machine: no background traffic to Google's hosts.
CHROMIUM_ARGS = [
    "--no-sandbox",
    "--disable-gpu",
    "--disable-quic",
    "--no-first-run",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
    # A synthetic camera that needs no permission prompt, for webcam-recorded answers.
    "--use-fake-device-for-media-stream",
    "--use-fake-ui-for-media-stream",
]


@pytest.fixture(scope="session")
def browser():
    """Headless Debian Chromium driven by Playwright; skipped loudly when not installed."""
    if not os.path.exists(CHROMIUM):
        message = f"BROWSER TESTS SKIPPED: {CHROMIUM} is missing (run `make test` as root)."
        if os.environ.get("SIGNSTUDY_REQUIRE_BROWSER"):
            pytest.fail(message)
        pytest.skip(message)
    from playwright.sync_api import sync_playwright

    # Playwright's sync API runs an event loop in the test thread; the ORM calls the
    # tests make there are still synchronous.
    os.environ["DJANGO_ALLOW_ASYNC_UNSAFE"] = "true"
    _server_requests()  # counting from before the first page opens (close_context waits)
    with sync_playwright() as playwright:
        chromium = playwright.chromium.launch(
            executable_path=CHROMIUM, headless=True, args=CHROMIUM_ARGS
        )
        yield chromium
        chromium.close()


class _ServerRequests:
    """Count the live server's requests in flight: its threads run in this process, so
    Django's request signals fire here."""

    def __init__(self) -> None:
        from django.core.signals import request_finished, request_started

        self.lock = threading.Lock()
        self.active = 0
        self.last_s = time.monotonic()
        request_started.connect(self._started, weak=False)
        request_finished.connect(self._finished, weak=False)

    def _started(self, **kwargs) -> None:
        with self.lock:
            self.active += 1
            self.last_s = time.monotonic()

    def _finished(self, **kwargs) -> None:
        with self.lock:
            self.active = max(0, self.active - 1)
            self.last_s = time.monotonic()

    def settle(self, quiet_s: float, timeout_s: float) -> None:
        """Wait until no request is in flight and none started for *quiet_s*."""
        deadline = time.monotonic() + timeout_s
        while time.monotonic() < deadline:
            with self.lock:
                if self.active == 0 and time.monotonic() - self.last_s >= quiet_s:
                    return
            time.sleep(0.02)


@functools.cache
def _server_requests() -> _ServerRequests:
    return _ServerRequests()


def close_context(context) -> None:
    """Close a browser context and wait for the requests its pages sent on closing.

    Closing hides a participant page, which sends its last events with keepalive; the
    live server must finish that request before pytest-django flushes the database, or
    PostgreSQL's TRUNCATE and the insert deadlock. The wait ends once the server has been
    idle for a quarter second (the keepalive request arrives within milliseconds).
    """
    requests = _server_requests()
    context.close()
    requests.settle(quiet_s=0.25, timeout_s=10.0)


@contextmanager
def browser_context(browser, **options):
    """Open a browser context for the block; close it (:func:`close_context`) however the
    block ends, so a failed test leaves no page calling the live server into the next."""
    context = browser.new_context(**options)
    try:
        yield context
    finally:
        close_context(context)


@pytest.fixture
def page(browser, _django_db_helper):
    """A fresh browser page; fails the test on any console error or page crash.

    It depends on pytest-django's database fixture so that it closes first: a page left
    open keeps sending events, which raced the database's flush after the test.

    A test that provokes errors on purpose (a lost connection) lists patterns of the
    ones it expects in ``page.allowed_errors``.
    """
    # Playwright's string predicates (wait_for_function) are evaluated with eval, which the
    # site's Content-Security-Policy forbids; test_security's browser test runs with it.
    context = browser.new_context(viewport={"width": 1280, "height": 900}, bypass_csp=True)
    page = context.new_page()
    page.allowed_errors = []
    errors = []
    page.on(
        "console",
        lambda msg: (
            errors.append(f"{msg.text} ({msg.location.get('url')})")
            if msg.type == "error"
            else None
        ),
    )
    page.on("pageerror", lambda error: errors.append(str(error)))
    page.on(
        "response",
        lambda response: (
            errors.append(f"HTTP {response.status} {response.url}")
            if response.status >= 400
            else None
        ),
    )
    yield page
    close_context(context)
    errors = [e for e in errors if not any(re.search(p, e) for p in page.allowed_errors)]
    assert errors == [], f"browser console errors: {errors}"


@pytest.fixture(scope="session")
def renderable():
    """Make sure an offscreen OpenGL context can be created; skip (or fail in CI) if not."""
    from synthesis.render.backend import RenderUnavailable, import_pyrender

    try:
        pyrender = import_pyrender()
        from synthesis.render.pyrender_compat import delete_offscreen

        delete_offscreen(pyrender.OffscreenRenderer(16, 16))
    except (RenderUnavailable, Exception) as error:  # any GL failure means "cannot render"
        message = f"RENDERING TESTS SKIPPED: no offscreen OpenGL here ({error})."
        if os.environ.get("SIGNSTUDY_REQUIRE_RENDER"):
            pytest.fail(message)
        pytest.skip(message)
    return pyrender


def as_draft(*studies) -> None:
    """Set studies back to draft: the demo studies are open, and an open design is locked."""
    for study in studies:
        study.status = "draft"
        study.save(update_fields=["status"])


def pytest_collection_modifyitems(config, items) -> None:
    """Mark the platform's tests ``database`` (only they touch one), and those that drive
    Chromium ``browser`` and ``slow``: scripts/test.sh runs the database tests on SQLite
    and PostgreSQL, the Chromium ones once (on PostgreSQL when it answers). ``release``
    tests run only when ``-m`` names them."""
    platform = Path(__file__).parent / "studyplatform"
    at_length = "release" in (config.getoption("markexpr") or "")
    for item in items:
        if "release" in item.keywords and not at_length:
            item.add_marker(pytest.mark.skip(reason="a release check: run with -m release"))
        if platform in Path(item.path).parents:
            item.add_marker(pytest.mark.database)
        if "browser" in getattr(item, "fixturenames", ()):
            item.add_marker(pytest.mark.browser)
            item.add_marker(pytest.mark.slow)
