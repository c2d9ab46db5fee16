"""Test that every text the researcher's pages show goes through gettext (issue 55, item 1).

The pages are rendered in a pseudo-language whose catalogue rewrites every message of
the project and of Django's admin into look-alike letters ("Ŝŧŭḓīḗş"). A run of plain
ASCII letters still on a page is then text that no catalogue can translate, unless it
is the study's own data (its title, keys, the researcher's texts) or a name.

Reference: the pseudo-localisation practice of Microsoft's and Mozilla's localisation
guides (every letter replaced by an accented form, placeholders and markup kept), and
GNU gettext's PO format and msgfmt.
"""

import json
import re
import subprocess
from html.parser import HTMLParser
from pathlib import Path

import django
import pytest
from django.apps import apps
from django.conf import settings
from django.contrib import admin
from django.contrib.auth import get_user_model
from django.db import models
from django.urls import URLPattern, reverse

from studyplatform.actions import do_duplicate_study
from studyplatform.models import Study
from synthesis.techniques import REGISTRY
from tests.studyplatform.test_results import take_spine_study
from tests.studyplatform.test_translations import LOCALE

pytestmark = pytest.mark.django_db

PSEUDO = "xx"
PLAIN = "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
LOOKALIKE = "ȧƀƈḓḗƒɠħīĵķŀḿƞǿƥɋřşŧŭṽẇẋẏẑȦƁƇḒḖƑƓĦĪĴĶĿḾȠǾƤɊŘŞŦŬṼẆẊẎẐ"
PSEUDO_LETTERS = str.maketrans(PLAIN, LOOKALIKE)
# What a translation keeps as it is: placeholders, markup and character references.
KEPT = re.compile(r"(%\(\w+\)[sdifr]|%[sdifr%]|\{\w*\}|<[^>]*>|&[#\w]+;)")
DJANGO = Path(django.__file__).parent
CATALOGUES = (
    LOCALE / "de" / "LC_MESSAGES" / "django.po",
    DJANGO / "conf" / "locale" / "en" / "LC_MESSAGES" / "django.po",
    DJANGO / "contrib" / "admin" / "locale" / "en" / "LC_MESSAGES" / "django.po",
    DJANGO / "contrib" / "auth" / "locale" / "en" / "LC_MESSAGES" / "django.po",
)


def pseudo(text: str) -> str:
    """Rewrite *text*'s letters as look-alikes, keeping placeholders and markup."""
    return "".join(
        part if KEPT.fullmatch(part) else part.translate(PSEUDO_LETTERS)
        for part in KEPT.split(text)
    )


def _po_string(text: str) -> str:
    return '"' + text.replace("\\", "\\\\").replace('"', '\\"').replace("\n", "\\n") + '"'


def _messages(path: Path) -> list[tuple[str, str | None, str | None]]:
    """Return each message id of a catalogue with its plural id and context, if any."""
    found = []
    for block in path.read_text("utf-8").strip().split("\n\n"):
        fields: dict[str, str] = {}
        current = None
        for line in block.split("\n"):
            field = re.match(r'^(msgctxt|msgid|msgid_plural) "(.*)"$', line)
            if field:
                current = field.group(1)
                fields[current] = field.group(2)
            elif line.startswith("msgstr"):
                current = None
            elif line.startswith('"') and current:
                fields[current] += line[1:-1]
        if fields.get("msgid"):
            plural = fields.get("msgid_plural")
            context = fields.get("msgctxt")
            found.append(
                (
                    _unescaped(fields["msgid"]),
                    _unescaped(plural) if plural else None,
                    _unescaped(context) if context else None,
                )
            )
    return found


def _unescaped(text: str) -> str:
    """Return a PO string's text (its backslash escapes read)."""
    escapes = {"n": "\n", "t": "\t", '"': '"', "\\": "\\"}
    return re.sub(r"\\(.)", lambda m: escapes.get(m.group(1), m.group(1)), text)


@pytest.fixture
def pseudo_language(settings, tmp_path):
    """Make the pseudo-language the researcher's, with every message rewritten."""
    lines = [
        'msgid ""',
        'msgstr ""',
        '"Content-Type: text/plain; charset=UTF-8\\n"',
        '"Plural-Forms: nplurals=2; plural=(n != 1);\\n"',
        "",
    ]
    seen = set()
    for catalogue in CATALOGUES:
        for msgid, plural, context in _messages(catalogue):
            if (context, msgid) in seen:
                continue
            seen.add((context, msgid))
            if context is not None:
                lines.append(f"msgctxt {_po_string(context)}")
            lines.append(f"msgid {_po_string(msgid)}")
            if plural is None:
                lines += [f"msgstr {_po_string(pseudo(msgid))}", ""]
            else:
                lines += [
                    f"msgid_plural {_po_string(plural)}",
                    f"msgstr[0] {_po_string(pseudo(msgid))}",
                    f"msgstr[1] {_po_string(pseudo(plural))}",
                    "",
                ]
    folder = tmp_path / PSEUDO / "LC_MESSAGES"
    folder.mkdir(parents=True)
    (folder / "django.po").write_text("\n".join(lines), "utf-8")
    subprocess.run(
        ["msgfmt", "-o", str(folder / "django.mo"), str(folder / "django.po")], check=True
    )
    settings.LOCALE_PATHS = [tmp_path, *settings.LOCALE_PATHS]
    settings.LANGUAGES = [*settings.LANGUAGES, (PSEUDO, "Pseudo")]
    settings.LANGUAGE_CODE = PSEUDO
    return PSEUDO


class _VisibleText(HTMLParser):
    """Collect the text a reader sees or hears: text nodes and labelling attributes."""

    # Not prose: scripts, styles, and commands or file names shown as code.
    HIDDEN = {"script", "style", "template", "code"}
    LABELS = ("title", "placeholder", "aria-label", "alt")

    def __init__(self, language: str) -> None:
        super().__init__(convert_charrefs=True)
        self.texts: list[str] = []
        self.language = language
        self._hidden = 0
        self._open: list[bool] = []

    def handle_starttag(self, tag, attrs):
        attributes = dict(attrs)
        # A participant's widgets in the study's language (the preview) are not the
        # researcher's text: an element in another language is skipped with its content.
        other = tag in self.HIDDEN or attributes.get("lang", self.language) != self.language
        if tag not in VOID:
            self._open.append(other)
        if other:
            self._hidden += 1
            if tag in VOID:
                self._hidden -= 1
            return
        if self._hidden:
            return
        self.texts += [attributes[name] or "" for name in self.LABELS if name in attributes]
        if tag == "input" and attributes.get("type") in ("submit", "button"):
            self.texts.append(attributes.get("value") or "")

    def handle_endtag(self, tag):
        if tag not in VOID and self._open and self._open.pop():
            self._hidden -= 1

    def handle_data(self, data):
        if not self._hidden:
            self.texts.append(data)


# Django's own pages show these untranslated: the search box's icon has alt="Search",
# a boolean column's icons alt="True" and alt="False".
DJANGO_UNTRANSLATED = {"Search", "True", "False"}
# Names: the product, and the multiple-comparison corrections named after their authors.
NAMES = {"SignStudy", "Holm", "Bonferroni", "Benjamini", "Hochberg", "holm"}
# What the researcher types as it is: a placeholder ({PROLIFIC_PID} in a redirect address)
# or a stored file's reference (recording:<id>).
PLACEHOLDER = re.compile(r"\{[A-Z_]+\}|\b[a-z_]+:<id>")
IDENTIFIER = re.compile(r"[a-z0-9_.:-]*")


def _researchers_texts_in_look_alikes() -> None:
    """Rewrite the researchers' own texts in the database (titles, labels, questions,
    consent …) into look-alike letters too: an English word left on a page is then
    never theirs, however common (the demo's texts are English prose)."""
    for model in apps.get_app_config("studyplatform").get_models():
        names = [
            f.attname
            for f in model._meta.concrete_fields
            if isinstance(f, models.CharField | models.TextField)
            and not isinstance(f, models.SlugField)
            and not f.choices
            and not f.unique
        ]
        for row in model.objects.values("pk", *names) if names else ():
            # Keys copied into other rows (a response's chosen condition) stay keys.
            changed = {
                name: pseudo(row[name])
                for name in names
                if row[name] and not IDENTIFIER.fullmatch(row[name])
            }
            model.objects.filter(pk=row["pk"]).update(**changed)


def _allowed_words() -> set[str]:
    """Return the words a page may show as they are: the keys the researchers chose (slugs)
    and settings stored as JSON, user names, names (the product, the interface's
    languages in their own words, the corrections' authors) and the citations that say
    where a technique comes from ("seed 003 §4")."""
    texts = [*NAMES, *DJANGO_UNTRANSLATED, *(name for _, name in settings.LANGUAGES)]
    texts += [technique.source or "" for technique in REGISTRY.techniques]
    texts += list(get_user_model().objects.values_list("username", flat=True))
    for model in apps.get_app_config("studyplatform").get_models():
        fields = [
            f.attname
            for f in model._meta.concrete_fields
            if isinstance(f, models.SlugField | models.JSONField)
            or (isinstance(f, models.CharField) and f.unique)  # tokens, codes
        ]
        for row in model.objects.values_list(*fields) if fields else ():
            texts += [json.dumps(value) if not isinstance(value, str) else value for value in row]
    return set(re.findall(r"[A-Za-z]+", " ".join(texts)))


VOID = {
    "area",
    "base",
    "br",
    "col",
    "embed",
    "hr",
    "img",
    "input",
    "link",
    "meta",
    "source",
    "track",
    "wbr",
}


def untranslated(html: str, allowed: set[str]) -> list[str]:
    """Return the texts of a page with a plain word that is neither data nor a name."""
    parser = _VisibleText(PSEUDO)
    parser.feed(html)
    return [
        text.strip()
        for text in parser.texts
        if any(
            word not in allowed for word in re.findall(r"[A-Za-z]{3,}", PLACEHOLDER.sub("", text))
        )
    ]


def _admin_pages(studies: list[Study]) -> list[str]:
    """Return the address of every page of the researcher's admin: each model's list, its
    add page and one row's page, the import page, and each of *studies*' own pages."""
    urls = [reverse("admin:index"), reverse("admin:studyplatform_study_import")]
    for model in admin.site._registry:
        name = f"admin:{model._meta.app_label}_{model._meta.model_name}"
        urls += [reverse(f"{name}_changelist"), reverse(f"{name}_add")]
        urls += [reverse(f"{name}_change", args=[row.pk]) for row in model.objects.all()[:1]]
    for study in studies:
        urls.append(reverse("admin:studyplatform_study_change", args=[study.pk]))
        urls += [
            reverse("admin:studyplatform_condition_change", args=[c.pk])
            for c in study.conditions.all()[:1]
        ]
        for pattern in admin.site._registry[Study].get_urls():
            route = str(pattern.pattern)
            if (
                isinstance(pattern, URLPattern)
                and (pattern.name or "").startswith("studyplatform_study_")
                and route.startswith("<path:object_id>/")
                and route.endswith("/")
                # Django's delete page lists its auto-made many-to-many rows by their
                # class names ("Trial_questions object (51)"), which no catalogue holds.
                and not pattern.name.endswith("_delete")
            ):
                urls.append(reverse(f"admin:{pattern.name}", args=[study.pk]))
    return list(dict.fromkeys(urls))


def test_every_researcher_page_shows_only_translated_text(client, bob, spine, pseudo_language):
    take_spine_study(spine)  # an open study with answers: its results, participants
    draft = do_duplicate_study(spine, owner=bob)  # a draft: its design can be edited
    client.force_login(bob)
    _researchers_texts_in_look_alikes()
    allowed = _allowed_words()
    found, shown = {}, 0
    for url in _admin_pages([spine, draft]):
        page = client.get(url)
        if page.status_code != 200 or "text/html" not in page["Content-Type"]:
            continue
        shown += 1
        assert f'lang="{pseudo_language}"' in page.text, url
        texts = untranslated(page.text, allowed)
        if texts:
            found[url] = [text[:160] for text in texts]
    assert shown >= 40
    assert found == {}


def test_an_untranslated_researcher_language_falls_back_to_english(client, bob, settings):
    """With SIGNSTUDY_LANGUAGE=de, Django's admin speaks German and SignStudy's texts,
    empty in the German catalogue, read in English (docs/translations.md)."""
    settings.LANGUAGE_CODE = "de"
    client.force_login(bob)
    page = client.get(reverse("admin:index")).text
    assert '<html lang="de"' in page and "Abmelden" in page
    assert "Studies, stimuli and responses" in page
