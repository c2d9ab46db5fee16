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
    return client.post(LOGIN, {"username": username, "password": password, "next": "/admin/"})


def _from(client, address: str, username: str, password: str):
    return client.post(
        LOGIN, {"username": username, "password": password, "next": "/admin/"}, REMOTE_ADDR=address
    )


def test_the_tenth_wrong_password_locks_the_account_and_the_address(client, alice, bob, settings):
    """Issue 33: the settings said the 11th failure locks (the 10th did), and a guesser
    with several addresses had ten tries at each."""
    assert settings.AXES_FAILURE_LIMIT == 10
    for attempt in range(9):  # three addresses share one count per account
        assert _from(client, f"10.0.0.{attempt % 3}", "alice", "wrong").status_code == 200
    assert _from(client, "10.0.0.0", "alice", "wrong").status_code == 429  # the 10th
    # Locked from every address, the right password too, without being checked.
    assert _from(client, "10.0.0.9", "alice", "pw-alice").status_code == 429
    assert "_auth_user_id" not in client.session
    # Another account from a fresh address is not locked …
    assert _from(client, "10.0.0.9", "bob", "pw-bob").status_code == 302
    client.logout()
    # … but ten failures from one address lock that address, whatever the user names.
    for attempt in range(10):
        _from(client, "10.0.1.1", f"nobody{attempt}", "wrong")
    assert _from(client, "10.0.1.1", "bob", "pw-bob").status_code == 429
    AccessAttempt.objects.all().delete()  # the cool-off's end
    assert _from(client, "10.0.1.1", "alice", "pw-alice").status_code == 302


def test_a_locked_account_still_opens_on_a_browser_that_signed_in_before(alice, settings):
    """Issue 33: ten failures sent by anyone locked the real researcher out, renewably."""
    from django.test import Client

    owner, attacker = Client(), Client()
    assert _from(owner, "10.0.0.5", "alice", "pw-alice").status_code == 302
    device = owner.cookies["signstudy_device"]
    assert device["httponly"] and device["path"] == "/admin/"

    def sign_out() -> None:  # the test client's logout forgets every cookie; a browser doesn't
        owner.logout()
        owner.cookies["signstudy_device"] = device.value

    sign_out()
    for _ in range(12):  # the attacker locks the account, from the owner's address even
        _from(attacker, "10.0.0.5", "alice", "wrong")
    assert _from(attacker, "10.0.0.5", "alice", "pw-alice").status_code == 429
    assert _from(owner, "10.0.0.5", "alice", "pw-alice").status_code == 302  # known device
    sign_out()
    # A known device that fails as often as the limit loses that standing.
    for _ in range(10):
        _from(owner, "10.0.0.5", "alice", "wrong")
    assert _from(owner, "10.0.0.5", "alice", "pw-alice").status_code == 429
    # A device cookie made for another user, or forged, counts for nothing.
    stranger = Client()
    stranger.cookies["signstudy_device"] = "forged:value"
    assert _from(stranger, "10.0.0.7", "alice", "pw-alice").status_code == 429


def test_a_device_cookie_forged_with_the_secret_key_bypasses_nothing(alice, settings):
    """Issue 51: with the key (read through a file parameter) an attacker signed "known
    device" cookies and 14 wrong passwords went uncounted. A device is the server's record
    now: a well-signed cookie without one counts every failure and opens no lock."""
    from django.core import signing
    from django.test import Client

    from studyplatform.admin.signin import DEVICE_COOKIE, DEVICE_SALT
    from studyplatform.models import KnownDevice

    forger = Client()
    forged = signing.dumps({"u": "alice", "d": "guessed-token"}, salt=DEVICE_SALT)
    for attempt in range(14):
        forger.cookies[DEVICE_COOKIE] = forged
        answer = _from(forger, "10.0.2.1", "alice", f"wrong-{attempt}")
        if attempt >= settings.AXES_FAILURE_LIMIT:
            assert answer.status_code == 429, attempt
    forger.cookies[DEVICE_COOKIE] = forged
    assert _from(forger, "10.0.2.1", "alice", "pw-alice").status_code == 429
    assert not KnownDevice.objects.exists()
    # The owner's real device, recorded at a sign-in before the attack, still opens.
    owner = Client()
    AccessAttempt.objects.all().delete()
    assert _from(owner, "10.0.2.9", "alice", "pw-alice").status_code == 302
    assert KnownDevice.objects.filter(user=alice).count() == 1
    device = owner.cookies[DEVICE_COOKIE].value
    for _ in range(12):
        forger.cookies[DEVICE_COOKIE] = forged
        _from(forger, "10.0.2.1", "alice", "wrong")
    owner.logout()
    owner.cookies[DEVICE_COOKIE] = device
    assert _from(owner, "10.0.2.9", "alice", "pw-alice").status_code == 302


def test_the_client_address_comes_from_a_proxy_only_when_it_is_trusted(rf, settings):
    from studyplatform.admin.signin import client_address

    request = rf.get("/", REMOTE_ADDR="127.0.0.1", HTTP_X_FORWARDED_FOR="6.6.6.6, 1.2.3.4")
    settings.SIGNSTUDY_TRUSTED_PROXIES = frozenset()
    assert client_address(request) == "127.0.0.1"  # nobody said to believe the header
    settings.SIGNSTUDY_TRUSTED_PROXIES = frozenset({"127.0.0.1"})
    assert client_address(request) == "1.2.3.4"  # the nearest hop the proxy saw
    settings.SIGNSTUDY_TRUSTED_PROXIES = frozenset({"127.0.0.1", "1.2.3.4"})
    assert client_address(request) == "6.6.6.6"


def test_weak_passwords_are_refused():
    for weak in ("12345678", "password", "short"):
        with pytest.raises(ValidationError):
            validate_password(weak)
    validate_password("a long and unusual passphrase 7")


def test_pages_carry_a_content_security_policy(client, fingerspelling, alice):
    participant = _start(client, fingerspelling)
    page = client.get(reverse("participant_page", args=[participant.token, 1]))
    policy = page["Content-Security-Policy"]
    for directive in (
        "default-src 'self'",
        "script-src 'self'",
        "object-src 'none'",
        "frame-ancestors 'none'",
        "form-action 'self'",
    ):
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
    env.update(
        SIGNSTUDY_VAR_DIR=str(tmp_path),
        SIGNSTUDY_HTTPS="1",
        SIGNSTUDY_ALLOWED_HOSTS="study.example.org",
    )
    check = subprocess.run(
        [sys.executable, "manage.py", "check", "--deploy", "--fail-level", "WARNING"],
        cwd=ROOT,
        env=env,
        capture_output=True,
        text=True,
    )
    assert check.returncode == 0, check.stdout + check.stderr
    assert "System check identified no issues (0 silenced)" in check.stdout or (
        "identified no issues" in check.stdout
    )
