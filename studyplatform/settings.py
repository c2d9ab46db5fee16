"""Configure the SignStudy Django project from environment variables.

Every setting has a safe default so that a fresh checkout runs on SQLite with no
configuration at all:

- ``DATABASE_URL``: e.g. ``postgres://postgres@127.0.0.1:5432/signstudy``; SQLite
  (``var/signstudy.sqlite3``, WAL mode) when unset.
- ``SIGNSTUDY_DEBUG``: ``1`` to turn debug mode on; off otherwise.
- ``SIGNSTUDY_SECRET_KEY``: the secret key; when unset, one is generated into
  ``var/secret_key`` on first run and reused afterwards (never committed);
  ``SIGNSTUDY_SECRET_KEY_FALLBACKS``: old keys still accepted while rotating.
- ``SIGNSTUDY_ALLOWED_HOSTS``: comma-separated host names (default: localhost names).
- ``SIGNSTUDY_VAR_DIR``: where local state lives (database, media, static, key).
- ``SIGNSTUDY_PRIVATE_MEDIA_ROOT``: where personal files live (default ``var/private``);
  ``SIGNSTUDY_SENDFILE_HEADER`` hands checked downloads of them to the web server.
- ``SIGNSTUDY_HTTPS``: ``1`` behind a TLS proxy: secure cookies, HTTPS redirect, HSTS
  (``SIGNSTUDY_HSTS_SECONDS``, default one year).
- ``SIGNSTUDY_LOGIN_FAILURE_LIMIT`` / ``SIGNSTUDY_LOGIN_COOLOFF_MINUTES``: failed admin
  sign-ins (per user name, and per address) before it is locked, and for how long;
  ``SIGNSTUDY_TRUSTED_PROXIES``: the proxies whose ``X-Forwarded-For`` names the client.
- ``CELERY_BROKER_URL`` / ``REDIS_URL``: the Redis broker for rendering jobs; jobs run
  in-process (eagerly) when neither is set.
"""

import contextlib
import os
import secrets
import tempfile
from datetime import timedelta
from pathlib import Path

import dj_database_url
from csp.constants import NONCE, NONE, SELF, UNSAFE_INLINE
from django.core.exceptions import ImproperlyConfigured

BASE_DIR = Path(__file__).resolve().parent.parent
# What the platform writes (the database, media, backups, keys, the ledger) is its own
# user's alone: files 0600, folders 0700. SIGNSTUDY_UMASK (octal) loosens it, e.g. 027
# when a web server of the same group serves MEDIA_ROOT (docs/deployment.md).
SIGNSTUDY_UMASK = int(os.environ.get("SIGNSTUDY_UMASK", "077"), 8)
os.umask(SIGNSTUDY_UMASK)
VAR_DIR = Path(os.environ.get("SIGNSTUDY_VAR_DIR", BASE_DIR / "var"))


def _env_flag(name: str, default: bool = False) -> bool:
    """Read a boolean environment variable ("1", "true", "yes", "on" are true)."""
    value = os.environ.get(name)
    if value is None:
        return default
    return value.strip().lower() in {"1", "true", "yes", "on"}


def _load_or_create_secret_key(path: Path) -> str:
    """Return the secret key stored at *path*, generating it on first use."""
    if path.exists():
        return path.read_text().strip()
    path.parent.mkdir(parents=True, exist_ok=True)
    # Written whole under a private name, then linked into place: two processes starting
    # at once must not write two keys, nor read the file before its key is in it.
    with tempfile.NamedTemporaryFile("w", dir=path.parent, prefix=".secret_key.") as draft:
        draft.write(secrets.token_urlsafe(50))
        draft.flush()
        os.fsync(draft.fileno())
        os.chmod(draft.name, 0o600)
        with contextlib.suppress(FileExistsError):  # another process linked first
            os.link(draft.name, path)
    return path.read_text().strip()


DEBUG = _env_flag("SIGNSTUDY_DEBUG")
SECRET_KEY = os.environ.get("SIGNSTUDY_SECRET_KEY") or _load_or_create_secret_key(
    VAR_DIR / "secret_key"
)
# Keys being retired (comma-separated): what they signed still reads while sessions
# and links move to the new key (docs/deployment.md, "Rotating the secret key").
SECRET_KEY_FALLBACKS = [
    key.strip()
    for key in os.environ.get("SIGNSTUDY_SECRET_KEY_FALLBACKS", "").split(",")
    if key.strip()
]
ALLOWED_HOSTS = [
    host.strip()
    for host in os.environ.get("SIGNSTUDY_ALLOWED_HOSTS", "localhost,127.0.0.1,[::1]").split(",")
    if host.strip()
]
CSRF_TRUSTED_ORIGINS = [
    origin.strip()
    for origin in os.environ.get("SIGNSTUDY_CSRF_TRUSTED_ORIGINS", "").split(",")
    if origin.strip()
]

INSTALLED_APPS = [
    "django.contrib.admin",
    "django.contrib.auth",
    "django.contrib.contenttypes",
    "django.contrib.sessions",
    "django.contrib.messages",
    "whitenoise.runserver_nostatic",
    "django.contrib.staticfiles",
    "axes",
    "csp",
    "studyplatform",
]

MIDDLEWARE = [
    "django.middleware.security.SecurityMiddleware",
    "studyplatform.middleware.RefuseNulMiddleware",
    "studyplatform.middleware.DatabaseUnavailableMiddleware",
    "whitenoise.middleware.WhiteNoiseMiddleware",
    "django.contrib.sessions.middleware.SessionMiddleware",
    "django.middleware.common.CommonMiddleware",
    "django.middleware.csrf.CsrfViewMiddleware",
    "django.contrib.auth.middleware.AuthenticationMiddleware",
    "django.contrib.messages.middleware.MessageMiddleware",
    "django.middleware.clickjacking.XFrameOptionsMiddleware",
    "csp.middleware.CSPMiddleware",
    "studyplatform.admin.signin.KnownDeviceMiddleware",
    "studyplatform.middleware.RefusedFormMiddleware",
    # Last, as django-axes asks: it turns a locked-out sign-in into its 429 answer.
    "axes.middleware.AxesMiddleware",
]

AUTHENTICATION_BACKENDS = [
    # First: refuses a locked-out user name and address before the password is checked.
    "axes.backends.AxesStandaloneBackend",
    "django.contrib.auth.backends.ModelBackend",
]

ROOT_URLCONF = "studyplatform.urls"
WSGI_APPLICATION = "studyplatform.wsgi.application"

TEMPLATES = [
    {
        "BACKEND": "django.template.backends.django.DjangoTemplates",
        # Searched before the apps' templates: the admin's own admin/base_site.html
        # would otherwise win over ours (django.contrib.admin comes first in the apps).
        "DIRS": [BASE_DIR / "studyplatform" / "templates"],
        "APP_DIRS": True,
        "OPTIONS": {
            "context_processors": [
                "django.template.context_processors.request",
                "django.template.context_processors.i18n",
                "django.contrib.auth.context_processors.auth",
                "django.contrib.messages.context_processors.messages",
            ],
        },
    },
]

_SQLITE_PATH = VAR_DIR / "signstudy.sqlite3"
# An empty DATABASE_URL means "unset" (dj_database_url would give no engine at all).
DATABASES = {
    "default": dj_database_url.parse(
        os.environ.get("DATABASE_URL") or f"sqlite:///{_SQLITE_PATH}",
        conn_max_age=60,
        conn_health_checks=True,
    )
}
if DATABASES["default"]["ENGINE"] == "django.db.backends.sqlite3":
    VAR_DIR.mkdir(parents=True, exist_ok=True)
    # No persistent connections on SQLite: each one is cheap, and WAL readers hold snapshots.
    DATABASES["default"]["CONN_MAX_AGE"] = 0
    DATABASES["default"]["OPTIONS"] = {
        # WAL lets participants' saves proceed while the admin reads; IMMEDIATE makes
        # writers queue on the busy timeout instead of failing with "database is locked".
        "init_command": "PRAGMA journal_mode=WAL; PRAGMA synchronous=NORMAL;",
        "transaction_mode": "IMMEDIATE",
        "timeout": 20,
    }
    # A file, not pytest's in-memory default: concurrency tests need real WAL locking.
    DATABASES["default"]["TEST"] = {"NAME": str(VAR_DIR / "test_signstudy.sqlite3")}

DEFAULT_AUTO_FIELD = "django.db.models.BigAutoField"

AUTH_PASSWORD_VALIDATORS = [
    {"NAME": "django.contrib.auth.password_validation.UserAttributeSimilarityValidator"},
    {"NAME": "django.contrib.auth.password_validation.MinimumLengthValidator"},
    {"NAME": "django.contrib.auth.password_validation.CommonPasswordValidator"},
    {"NAME": "django.contrib.auth.password_validation.NumericPasswordValidator"},
]

# The researcher's pages are in LANGUAGE_CODE (SIGNSTUDY_LANGUAGE, one of LANGUAGES);
# a participant's in their study's language (Study.language: the interface's catalogues
# in studyplatform/locale, made as docs/translations.md says). No LocaleMiddleware: a
# browser's language changes a participant's pages only where their study allows it.
LANGUAGES = [
    ("en", "English"),
    ("pt-br", "Português (Brasil)"),
    ("tr", "Türkçe"),
    ("es", "Español"),
    ("fr", "Français"),
    ("de", "Deutsch"),
]
LANGUAGE_CODE = os.environ.get("SIGNSTUDY_LANGUAGE", "en")
if LANGUAGE_CODE not in dict(LANGUAGES):
    raise ImproperlyConfigured(
        f"SIGNSTUDY_LANGUAGE={LANGUAGE_CODE!r} is not one of the interface's languages "
        f"({', '.join(dict(LANGUAGES))})."
    )
LOCALE_PATHS = [BASE_DIR / "studyplatform" / "locale"]
TIME_ZONE = "UTC"
USE_I18N = True
USE_TZ = True

STATIC_URL = "static/"
STATIC_ROOT = Path(os.environ.get("SIGNSTUDY_STATIC_ROOT", VAR_DIR / "static"))
MEDIA_URL = "media/"
MEDIA_ROOT = Path(os.environ.get("SIGNSTUDY_MEDIA_ROOT", VAR_DIR / "media"))
STORAGES = {
    "default": {"BACKEND": "studyplatform.files.storage.MediaStorage"},
    "staticfiles": {
        "BACKEND": (
            "django.contrib.staticfiles.storage.StaticFilesStorage"
            if DEBUG
            else "whitenoise.storage.CompressedManifestStaticFilesStorage"
        )
    },
}
# Personal files (signed answers, signers' recordings, unfinished uploads) live outside
# MEDIA_ROOT: no URL maps to them except the authenticated view (docs/deployment.md).
SIGNSTUDY_PRIVATE_MEDIA_ROOT = Path(
    os.environ.get("SIGNSTUDY_PRIVATE_MEDIA_ROOT", VAR_DIR / "private")
)
for _directory in (STATIC_ROOT, MEDIA_ROOT, SIGNSTUDY_PRIVATE_MEDIA_ROOT):
    _directory.mkdir(parents=True, exist_ok=True)
FILE_UPLOAD_PERMISSIONS = 0o666 & ~SIGNSTUDY_UMASK
FILE_UPLOAD_DIRECTORY_PERMISSIONS = 0o777 & ~SIGNSTUDY_UMASK
# Serve public media (stimulus clips, ASL prompts) through Django; a large deployment
# puts a web server or object store in front instead.
SIGNSTUDY_SERVE_MEDIA = _env_flag("SIGNSTUDY_SERVE_MEDIA", default=True)
# Let the web server send private files once Django has checked access: "X-Accel-Redirect"
# (nginx, to the internal location SIGNSTUDY_SENDFILE_PREFIX) or "X-Sendfile" (Apache's
# mod_xsendfile, with the file's absolute path); empty: Django sends them itself.
SIGNSTUDY_SENDFILE_HEADER = os.environ.get("SIGNSTUDY_SENDFILE_HEADER", "")
SIGNSTUDY_SENDFILE_PREFIX = os.environ.get("SIGNSTUDY_SENDFILE_PREFIX", "/protected/")
# The append-only record of withdrawals that a restore re-applies (studyplatform.files.ledger):
# outside the database and the media roots, so neither a restore nor a flush replaces it.
SIGNSTUDY_WITHDRAWAL_LEDGER = Path(
    os.environ.get("SIGNSTUDY_WITHDRAWAL_LEDGER", VAR_DIR / "withdrawals.jsonl")
)
# An upload nobody has added to for this long was abandoned: `clean_uploads` removes it.
SIGNSTUDY_PARTIAL_UPLOAD_MAX_AGE_HOURS = float(
    os.environ.get("SIGNSTUDY_PARTIAL_UPLOAD_MAX_AGE_HOURS", "24")
)

LOGIN_URL = "admin:login"
CSRF_FAILURE_VIEW = "studyplatform.views.errors.csrf_failure"

SESSION_COOKIE_HTTPONLY = True
CSRF_COOKIE_HTTPONLY = False
SECURE_CONTENT_TYPE_NOSNIFF = True
X_FRAME_OPTIONS = "DENY"
if _env_flag("SIGNSTUDY_HTTPS"):
    SESSION_COOKIE_SECURE = True
    CSRF_COOKIE_SECURE = True
    SECURE_PROXY_SSL_HEADER = ("HTTP_X_FORWARDED_PROTO", "https")
    SECURE_SSL_REDIRECT = True
    SECURE_HSTS_SECONDS = int(os.environ.get("SIGNSTUDY_HSTS_SECONDS", str(365 * 24 * 3600)))
    SECURE_HSTS_INCLUDE_SUBDOMAINS = _env_flag("SIGNSTUDY_HSTS_INCLUDE_SUBDOMAINS")
    SECURE_HSTS_PRELOAD = _env_flag("SIGNSTUDY_HSTS_PRELOAD")
    # Django's check warns about these two only when HSTS covers subdomains and preloads;
    # whether to do that is the site's decision (docs/deployment.md).
    if not (SECURE_HSTS_INCLUDE_SUBDOMAINS and SECURE_HSTS_PRELOAD):
        SILENCED_SYSTEM_CHECKS = ["security.W005", "security.W021"]

# Content-Security-Policy (django-csp): scripts only from this site or with the response's
# nonce (the admin pages' two small inline scripts); recorded answers play from blob: URLs,
# figures are data: PNGs. Inline styles stay allowed (style attributes size the clips).
CONTENT_SECURITY_POLICY = {
    "DIRECTIVES": {
        "default-src": [SELF],
        "script-src": [SELF, NONCE],
        "style-src": [SELF, UNSAFE_INLINE],
        "img-src": [SELF, "data:", "blob:"],
        "media-src": [SELF, "blob:"],
        "connect-src": [SELF],
        "object-src": [NONE],
        "base-uri": [SELF],
        "form-action": [SELF],
        "frame-ancestors": [NONE],
    }
}

# django-axes (studyplatform.admin.signin): the 10th failed sign-in of a user name within the
# cool-off, from any addresses, locks that name, and the 10th from one address locks that
# address: until the cool-off ends every sign-in there is refused (429) without checking
# the password. A browser that signed in as the user before is not locked by it.
AXES_FAILURE_LIMIT = int(os.environ.get("SIGNSTUDY_LOGIN_FAILURE_LIMIT", "10"))
AXES_COOLOFF_TIME = timedelta(
    minutes=float(os.environ.get("SIGNSTUDY_LOGIN_COOLOFF_MINUTES", "15"))
)
AXES_LOCKOUT_PARAMETERS = ["username", "ip_address"]
AXES_WHITELIST_CALLABLE = "studyplatform.admin.signin.is_known_device"
AXES_CLIENT_IP_CALLABLE = "studyplatform.admin.signin.client_address"
# The reverse proxies whose X-Forwarded-For is believed (comma-separated addresses);
# none by default: then the client is REMOTE_ADDR (docs/deployment.md).
SIGNSTUDY_TRUSTED_PROXIES = frozenset(
    a.strip() for a in os.environ.get("SIGNSTUDY_TRUSTED_PROXIES", "").split(",") if a.strip()
)
# A success does not clear the failures counted: an owner signing in must not reopen
# their account to the guesser who locked it.
AXES_RESET_ON_SUCCESS = False
AXES_VERBOSE = False  # its banner on every start; lockouts are logged all the same

_BROKER_URL = os.environ.get("CELERY_BROKER_URL") or os.environ.get("REDIS_URL") or ""
# Without a broker (the demo's default) jobs run in the calling process; the in-memory
# transport keeps kombu from warning about (and defaulting to) an AMQP server on localhost.
CELERY_TASK_ALWAYS_EAGER = not _BROKER_URL
CELERY_BROKER_URL = _BROKER_URL or "memory://localhost/"
CELERY_RESULT_BACKEND = os.environ.get("CELERY_RESULT_BACKEND") or _BROKER_URL or None
CELERY_TASK_EAGER_PROPAGATES = True
# Acknowledge after success so a killed worker's job is redelivered, not lost.
CELERY_TASK_ACKS_LATE = True
CELERY_TASK_REJECT_ON_WORKER_LOST = True
CELERY_WORKER_PREFETCH_MULTIPLIER = 1
# `celery -A studyplatform.celery beat` runs these; without beat, cron runs
# `manage.py clean_uploads` instead (docs/deployment.md).
CELERY_BEAT_SCHEDULE = {
    "clean-abandoned-uploads": {
        "task": "studyplatform.clean_abandoned_uploads",
        "schedule": 3600.0,
    },
    "apply-retention": {"task": "studyplatform.apply_retention", "schedule": 24 * 3600.0},
}

LOG_LEVEL = os.environ.get("SIGNSTUDY_LOG_LEVEL", "INFO").upper()
LOGGING = {
    "version": 1,
    "disable_existing_loggers": False,
    "handlers": {"console": {"class": "logging.StreamHandler"}},
    "root": {"handlers": ["console"], "level": LOG_LEVEL},
    # Jobs run in the calling process report themselves (generate_stimuli prints each
    # clip); Celery's per-task lines would repeat that. A real worker logs them.
    "loggers": {
        "celery.app.trace": {"level": "WARNING" if CELERY_TASK_ALWAYS_EAGER else "INFO"},
        # Every sign-in would be an INFO line; lockouts are warnings.
        "axes": {"level": "WARNING"},
    },
}
