"""Throttle admin sign-ins so that guessing is slow and the owner is never locked out.

django-axes counts failed sign-ins; its rules here (settings ``AXES_*``):

- **by account, across addresses**: the ``SIGNSTUDY_LOGIN_FAILURE_LIMIT``-th failure
  (default 10) within the cool-off locks the user name, from every address, so a guesser
  with many addresses gets no more tries than one with one;
- **by address**: as many failures from one address, whatever user names, lock it;
- **known devices**: a browser that has signed in as a user before carries a signed
  cookie naming that user and a random token (:data:`DEVICE_COOKIE`), whose SHA-256 the
  server keeps (:class:`~studyplatform.models.KnownDevice`); a cookie without its row,
  however well signed, is no device (issue 51: with a leaked secret key, forged cookies
  let wrong passwords through uncounted). For a known device that user's lock does not apply,
  so an attacker who locks an account locks out nobody who has signed in before; a device
  that fails as often as the limit loses that standing until its cool-off ends.
  A new browser of a locked account waits for the cool-off, or an administrator runs
  ``manage.py axes_reset_username <name>``.

The client's address is ``REMOTE_ADDR``, unless that is one of ``SIGNSTUDY_TRUSTED_PROXIES``:
then it is the nearest address in ``X-Forwarded-For`` that is not a trusted proxy. A
header nobody configured is never believed (issue 33: ten failures sent through the proxy
locked the real admin out, and a spoofed header chose whom to lock).
"""

import hashlib
import secrets
from datetime import timedelta

from django.conf import settings
from django.contrib.auth.signals import user_logged_in, user_login_failed
from django.core import signing
from django.core.cache import cache
from django.dispatch import receiver
from django.http import HttpRequest
from django.utils import timezone

from studyplatform.models import KnownDevice

DEVICE_COOKIE = "signstudy_device"
DEVICE_SALT = "studyplatform.admin.signin.device"
DEVICE_MAX_AGE_S = 180 * 24 * 3600


def client_address(request: HttpRequest) -> str:
    """Return the address a request came from (see the module's note on proxies)."""
    remote = request.META.get("REMOTE_ADDR", "")
    trusted = settings.SIGNSTUDY_TRUSTED_PROXIES
    if remote not in trusted:
        return remote
    forwarded = [a.strip() for a in request.META.get("HTTP_X_FORWARDED_FOR", "").split(",")]
    for address in reversed([a for a in forwarded if a]):
        if address not in trusted:
            return address[:45]  # the longest textual IPv6 address
    return remote


def _username(credentials) -> str:
    return str((credentials or {}).get("username", ""))


def _device(request: HttpRequest) -> tuple[str, str] | None:
    """Return the (user name, device id) of the request's known-device cookie, if valid."""
    value = request.COOKIES.get(DEVICE_COOKIE, "")
    try:
        data = signing.loads(value, salt=DEVICE_SALT, max_age=DEVICE_MAX_AGE_S)
    except signing.BadSignature:
        return None
    if not isinstance(data, dict) or not all(isinstance(data.get(k), str) for k in "ud"):
        return None
    return data["u"], data["d"]


def _device_failures_key(device_id: str) -> str:
    return f"signstudy:device-failures:{device_id}"


def _token_sha256(token: str) -> str:
    return hashlib.sha256(token.encode()).hexdigest()


def _recent_devices():
    since = timezone.now() - timedelta(seconds=DEVICE_MAX_AGE_S)
    return KnownDevice.objects.filter(created_at__gte=since)


def is_known_device(request: HttpRequest, credentials=None) -> bool:
    """Return whether the request comes from a device that signed in as this user before,
    and has not failed as often as the limit since (axes' whitelist: never locked)."""
    device = _device(request)
    if device is None or device[0] != _username(credentials) or not device[0]:
        return False
    if cache.get(_device_failures_key(device[1]), 0) >= settings.AXES_FAILURE_LIMIT:
        return False
    return (
        _recent_devices()
        .filter(user__username=device[0], token_sha256=_token_sha256(device[1]))
        .exists()
    )


@receiver(user_login_failed)
def note_failure(sender, credentials=None, request=None, **kwargs) -> None:
    """Count a failure against the request's known device, if it has one."""
    device = _device(request) if request is not None else None
    if device is None:
        return
    key = _device_failures_key(device[1])
    timeout = int(settings.AXES_COOLOFF_TIME.total_seconds())
    if not cache.add(key, 1, timeout):
        try:
            cache.incr(key)
        except ValueError:  # expired meanwhile
            cache.add(key, 1, timeout)


@receiver(user_logged_in)
def remember_device(sender, request=None, user=None, **kwargs) -> None:
    """Mark the browser that just signed in as a known device of *user*."""
    if request is None or user is None:
        return
    token = secrets.token_urlsafe(24)
    KnownDevice.objects.create(user=user, token_sha256=_token_sha256(token))
    # Devices past their age are no longer known: drop them as a new one comes.
    old = timezone.now() - timedelta(seconds=DEVICE_MAX_AGE_S)
    KnownDevice.objects.filter(user=user, created_at__lt=old).delete()
    value = signing.dumps({"u": user.get_username(), "d": token}, salt=DEVICE_SALT)
    request.signstudy_device_cookie = value


class KnownDeviceMiddleware:
    """Set the known-device cookie on the response to a successful sign-in."""

    def __init__(self, get_response):
        self.get_response = get_response

    def __call__(self, request: HttpRequest):
        response = self.get_response(request)
        value = getattr(request, "signstudy_device_cookie", None)
        if value:
            response.set_cookie(
                DEVICE_COOKIE,
                value,
                max_age=DEVICE_MAX_AGE_S,
                httponly=True,
                secure=settings.SESSION_COOKIE_SECURE,
                samesite="Lax",
                path="/admin/",
            )
        return response
