"""Test the participant interface in the study's language (issue 55, item 1).

References: Django's translation documentation (makemessages, compilemessages,
JavaScriptCatalog) and GNU gettext's msgfmt, whose ``--check-format`` compares each
translation's placeholders with its message id's.
"""

import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
from django.conf import settings
from django.urls import reverse
from django.utils.translation import to_locale

from studyplatform.models import Participant, Study
from tests.studyplatform.test_participate import _start

ROOT = Path(__file__).resolve().parents[2]
LOCALE = ROOT / "studyplatform" / "locale"
DOMAINS = ("django", "djangojs")
# The researcher's pages (the admin, the models' field names and help, the checks'
# messages): marked for translation, complete in English; another language's catalogue
# may leave them empty (docs/translations.md). Every other message is a participant's.
RESEARCHER_PATHS = (
    "admin",
    "models",
    "rules",
    "templates/admin",
    "lib/preview.py",
    "lib/roster.py",
    "lib/stimuli.py",
    "lib/uploads.py",
)


def _entries(path: Path) -> dict[str, list[str]]:
    """Return a catalogue's message ids with their translations (plural forms listed)."""
    entries: dict[str, list[str]] = {}
    for block in path.read_text("utf-8").strip().split("\n\n"):
        parts: dict[str, list[str]] = {}
        current = None
        for line in block.split("\n"):
            field = re.match(r'^(msgid|msgid_plural|msgstr(?:\[\d\])?) "(.*)"$', line)
            if field:
                current = field.group(1)
                parts[current] = [field.group(2)]
            elif line.startswith('"') and current:
                parts[current].append(line[1:-1])
        msgid = "".join(parts.get("msgid", []))
        if msgid:
            entries[msgid] = ["".join(v) for k, v in parts.items() if k.startswith("msgstr")]
    return entries


def _languages() -> list[str]:
    return [code for code, _ in settings.LANGUAGES if code != settings.LANGUAGE_CODE]


def _make_messages(root: Path, copy: Path, domain: str, ignored: tuple[str, ...] = ()) -> None:
    """Copy the platform to *copy* and run makemessages there, leaving out the *ignored*
    paths of studyplatform (folders or files)."""
    shutil.copytree(
        root / "studyplatform",
        copy / "studyplatform",
        ignore=shutil.ignore_patterns("__pycache__", "*.mo"),
        dirs_exist_ok=True,
    )
    shutil.copy(root / "manage.py", copy / "manage.py")
    languages = [arg for code in _languages() for arg in ("-l", to_locale(code))]
    # makemessages matches an ignore pattern against each path it walks ("studyplatform/…").
    patterns = [arg for path in ignored for arg in ("-i", f"studyplatform/{path}")]
    subprocess.run(
        [
            *(sys.executable, "manage.py", "makemessages", "-d", domain, *languages),
            *("--no-location", "--no-obsolete", "-v0", *patterns),
        ],
        cwd=copy,
        env={"PYTHONPATH": f"{copy}:{ROOT}", "PATH": "/usr/bin:/bin"},
        check=True,
    )


@pytest.fixture(scope="module")
def participant_messages(tmp_path_factory) -> dict[str, set[str]]:
    """Return the message ids of the participant's pages, per domain: those makemessages
    finds with the researcher's files left out."""
    found = {}
    for domain in DOMAINS:
        copy = tmp_path_factory.mktemp(f"participant-{domain}")
        _make_messages(ROOT, copy, domain, RESEARCHER_PATHS)
        path = copy / "studyplatform" / "locale" / "de" / "LC_MESSAGES" / f"{domain}.po"
        found[domain] = set(_entries(path))
    return found


@pytest.mark.parametrize("code", _languages())
def test_every_catalogue_is_complete_and_keeps_every_placeholder(code, participant_messages):
    """Each interface language translates every participant message of both domains,
    none fuzzy, and msgfmt finds each translation's placeholders the same as its
    message id's."""
    for domain in DOMAINS:
        path = LOCALE / to_locale(code) / "LC_MESSAGES" / f"{domain}.po"
        entries = _entries(path)
        assert len(participant_messages[domain]) > (80 if domain == "django" else 30), path
        untranslated = [
            msgid
            for msgid in participant_messages[domain]
            if msgid not in entries or not all(entries[msgid])
        ]
        assert untranslated == [], path
        assert "#, fuzzy" not in path.read_text("utf-8")
        checked = subprocess.run(
            ["msgfmt", "--check", "-o", "/dev/null", str(path)], capture_output=True, text=True
        )
        assert checked.returncode == 0, checked.stderr


def test_the_catalogues_hold_every_message_the_code_marks(tmp_path):
    """makemessages run on a copy of the platform finds no message the catalogues lack
    and none they keep that the code no longer has."""
    for domain in DOMAINS:
        _make_messages(ROOT, tmp_path, domain)
    for code in _languages():
        for domain in DOMAINS:
            relative = Path(to_locale(code)) / "LC_MESSAGES" / f"{domain}.po"
            made = _entries(tmp_path / "studyplatform" / "locale" / relative)
            assert set(made) == set(_entries(LOCALE / relative))


@pytest.fixture
def turkish(spine):
    Study.objects.filter(pk=spine.pk).update(language="tr", sign_language="TİD")
    spine.refresh_from_db()
    return spine


def test_a_turkish_study_speaks_turkish_from_welcome_to_thanks(client, turkish):
    welcome = client.get(reverse("study_welcome", args=[turkish.slug]))
    assert '<html lang="tr"' in welcome.text and welcome["Content-Language"] == "tr"
    assert "Onam" in welcome.text and "Consent</h2>" not in welcome.text
    participant = _start(client, turkish)
    page = client.get(reverse("participant_page", args=[participant.token, 1]))
    assert "Sayfa 1 / " in page.text and "Skip to content" not in page.text
    assert reverse("javascript_catalog", args=["tr"]) in page.text
    refused = client.post(
        reverse("participant_page", args=[participant.token, 1]),
        {"nav": "next"},
        HTTP_ACCEPT="application/json",
    )
    if refused.status_code == 400:  # a page with required questions
        assert "Lütfen" in refused.json()["error"]
    catalogue = client.get(reverse("javascript_catalog", args=["tr"]))
    assert catalogue.status_code == 200 and "Kaydediliyor" in catalogue.text


def test_the_sign_language_is_named_as_the_study_names_it(client, turkish):
    Study.objects.filter(pk=turkish.pk).update(asl_first=True, allow_english_only=True)
    participant = _start(client, turkish)
    page = client.get(reverse("participant_page", args=[participant.token, 1]))
    assert "Yalnızca yazılı metne geç" in page.text
    Participant.objects.filter(pk=participant.pk).update(language="en")
    page = client.get(reverse("participant_page", args=[participant.token, 1]))
    assert "TİD ve yazılı metne geç" in page.text and "ASL ve" not in page.text


def test_the_browser_language_counts_only_where_the_study_allows_it(client, spine):
    url = reverse("study_welcome", args=[spine.slug])
    german = {"HTTP_ACCEPT_LANGUAGE": "ja;q=1, de-AT;q=0.8, en;q=0.5"}
    assert client.get(url, **german)["Content-Language"] == "en"
    Study.objects.filter(pk=spine.pk).update(language="pt-br", follow_browser_language=True)
    assert client.get(url, **german)["Content-Language"] == "de"
    assert "Einwilligung" in client.get(url, **german).text
    unknown = client.get(url, HTTP_ACCEPT_LANGUAGE="ja, zh;q=0.9")
    assert unknown["Content-Language"] == "pt-br" and "Consentimento" in unknown.text
    # The researcher's pages stay in the project's language whatever the browser says.
    admin = client.get(reverse("admin:login"), **german)
    assert '<html lang="en"' in admin.text and "Anmelden" not in admin.text


def test_an_unknown_catalogue_language_is_not_found(client):
    assert client.get(reverse("javascript_catalog", args=["xx"])).status_code == 404
    assert client.get(reverse("javascript_catalog", args=["en"])).status_code == 200
