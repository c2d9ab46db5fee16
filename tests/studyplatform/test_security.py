"""Sign-in throttling, password rules, security headers and the deployment check (issue 19)."""

import os
import subprocess
import sys

import pytest
from axes.models import AccessAttempt
from django.contrib.auth.password_validation import validate_password
from django.core.exceptions import ValidationError
from django.urls import reverse

from tests.studyplatform.test_participate import _start
from tests.studyplatform.test_settings import ROOT

pytestmark = pytest.mark.django_db

LOGIN = "/admin/login/"


def _sign_in(client, username: str, password: str):
    return client.post(LOGIN, {"username": username, "password": password,
                               "next": "/admin/"})  # fmt: skip


def test_the_eleventh_wrong_password_is_throttled(client, alice, settings):
    assert settings.AXES_FAILURE_LIMIT == 10
    for _ in range(10):
        wrong = _sign_in(client, "alice", "not-her-password")
        assert wrong.status_code in (200, 429)
    throttled = _sign_in(client, "alice", "still-wrong")
    assert throttled.status_code == 429
    # Locked: even the right password is refused, without being checked, until the cool-off.
    assert _sign_in(client, "alice", "pw-alice").status_code == 429
    assert "_auth_user_id" not in client.session
    # Another user name from the same address is not locked.
    assert _sign_in(client, "bob", "wrong").status_code == 200
    # After the cool-off the right password works again.
    AccessAttempt.objects.all().delete()
    assert _sign_in(client, "alice", "pw-alice").status_code == 302


def test_weak_passwords_are_refused():
    for weak in ("12345678", "password", "short"):
        with pytest.raises(ValidationError):
            validate_password(weak)
    validate_password("a long and unusual passphrase 7")


def test_pages_carry_a_content_security_policy(client, fingerspelling, alice):
    participant = _start(client, fingerspelling)
    page = client.get(reverse("participant_page", args=[participant.token, 1]))
    policy = page["Content-Security-Policy"]
    for directive in ("default-src 'self'", "script-src 'self'", "object-src 'none'",
                      "frame-ancestors 'none'", "form-action 'self'"):  # fmt: skip
        assert directive in policy
    assert "unsafe-eval" not in policy and "'unsafe-inline'" not in policy.split("style-src")[0]
    client.force_login(alice)
    stimuli = client.get(reverse("admin:studyplatform_study_stimuli", args=[fingerspelling.pk]))
    # django-csp adds the nonce only to a response that used it.
    nonce = stimuli["Content-Security-Policy"].split("script-src 'self' 'nonce-")[1].split("'")[0]
    assert f'<script nonce="{nonce}">' in stimuli.text  # its inline script may run


def test_the_deployment_check_is_clean_with_https(tmp_path):
    # Neither the test database nor the browser tests' async switch is a deployment's.
    skip = ("SIGNSTUDY_", "DATABASE_URL", "DJANGO_ALLOW_ASYNC_UNSAFE")
    env = {k: v for k, v in os.environ.items() if not k.startswith(skip)}
    env.update(SIGNSTUDY_VAR_DIR=str(tmp_path), SIGNSTUDY_HTTPS="1",
               SIGNSTUDY_ALLOWED_HOSTS="study.example.org")  # fmt: skip
    check = subprocess.run(
        [sys.executable, "manage.py", "check", "--deploy", "--fail-level", "WARNING"],
        cwd=ROOT, env=env, capture_output=True, text=True,
    )  # fmt: skip
    assert check.returncode == 0, check.stdout + check.stderr
    assert "System check identified no issues (0 silenced)" in check.stdout or (
        "identified no issues" in check.stdout
    )
