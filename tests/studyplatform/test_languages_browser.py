"""A Turkish and a Brazilian Portuguese study, built in the admin and taken in Chromium.

Issue 55's first acceptance point. A researcher builds each study on the admin's study
page (its language, sign language and manual alphabet, a condition, words, an
intelligibility question), builds its pages with the design builder, gets its clips
(the Turkish study's are uploaded films of TİD, which the engine does not render; the
Brazilian study's are rendered in the Libras alphabet, whose Ç the ASL one lacks) and
opens it. A participant takes it in Chromium: every page is in the study's language (its
``lang``, its buttons, the messages participate.js shows), and the words typed with Ç,
Ğ, İ, ã and ç are scored in the downloaded report as the letters say: "çay" is ÇAY,
"iki" is İKİ (Turkish capitals: i ↔ İ), "dag" is not DAĞ, "maçã" is MAÇÃ, "casa" is not
CAÇA (one letter makes another word; too short for a misspelling to count).
"""

import csv
import gettext
import io
import zipfile
from pathlib import Path

import pytest
from django.conf import settings
from django.utils import translation
from playwright.sync_api import expect

from studyplatform.models import Condition, Participant, Study, Trial
from tests.conftest import close_context
from tests.studyplatform.taking import download_report, generate_and_open, sign_in_at
from tests.studyplatform.test_uploaded_clips import make_video

pytestmark = pytest.mark.django_db(transaction=True)

SCREENSHOTS = Path(__file__).resolve().parents[2] / "test-results"

# English interface texts that must not show on a translated participant page.
ENGLISH = ("Next", "Finish", "Answer saved.", "Play Clip", "Page ", "Continue (I agree")

TURKISH = {
    "language": "tr",
    "sign_language": "TİD",
    "manual_alphabet": "asl",
    "title": "Türkçe kelimeler",
    "slug": "turkce-kelimeler",
    "question": "Hangi kelimeyi gördünüz?",
    # key, text, target text, typed answer, its score
    "items": [
        ("cay", "ÇAY", "", "çay", 1.0),
        ("dag", "DAĞ", "", "dag", 0.0),
        ("iki", "İKİ", "", "iki", 1.0),
    ],
}
PORTUGUESE = {
    "language": "pt-br",
    "sign_language": "Libras",
    "manual_alphabet": "libras",
    "title": "Soletração em Libras",
    "slug": "soletracao-em-libras",
    "question": "Qual palavra foi soletrada?",
    # MAÇÃ is spelled without its tilde (Ã is not in the alphabet file) and scored with it.
    "items": [
        ("caca", "CAÇA", "", "casa", 0.0),
        ("maca", "MAÇA", "MAÇÃ", "maçã", 1.0),
    ],
}


def _save(page) -> None:
    page.get_by_role("button", name="Save and continue editing").click()
    page.wait_for_load_state("load")
    errors = page.locator(".errorlist, .errornote").all_text_contents()
    assert not errors, errors
    expect(page.locator(".messagelist .success")).to_be_visible()


def _build(page, url: str, spec: dict, uploaded: bool) -> Study:
    """Add the study on the admin's study page and build its pages with the builder."""
    sign_in_at(page, url, "/admin/studyplatform/study/add/")
    page.get_by_label("Title").fill(spec["title"])
    page.get_by_label("Title").press("Tab")
    expect(page.get_by_label("Slug")).to_have_value(spec["slug"])  # made from the title
    page.locator("#id_language").select_option(spec["language"])
    page.locator("#id_sign_language").fill(spec["sign_language"])
    page.locator("#id_manual_alphabet").select_option(spec["manual_alphabet"])
    page.get_by_role("button", name="Add another Condition").click()
    page.locator('[name="conditions-0-key"]').fill("signer")
    page.locator('[name="conditions-0-label"]').fill(spec["sign_language"])
    if uploaded:
        page.locator('[name="conditions-0-source"]').select_option("uploaded")
    for index, (key, text, target, _, _) in enumerate(spec["items"]):
        page.get_by_role("button", name="Add another Item").click()
        page.locator(f'[name="items-{index}-key"]').fill(key)
        page.locator(f'[name="items-{index}-text"]').fill(text)
        page.locator(f'[name="items-{index}-target_text"]').fill(target)
    page.get_by_role("button", name="Add another Question").click()
    page.locator('[name="questions-0-key"]').fill("word")
    page.locator('[name="questions-0-kind"]').select_option("intelligibility")
    page.locator('[name="questions-0-text"]').fill(spec["question"])
    _save(page)
    study = Study.objects.get(title=spec["title"])
    assert study.slug == spec["slug"], study.slug
    assert (study.language, study.manual_alphabet) == (spec["language"], spec["manual_alphabet"])
    if not uploaded:  # small and quick to render
        condition = Condition.objects.get(study=study, key="signer")
        page.goto(f"{url}/admin/studyplatform/condition/{condition.pk}/change/")
        for label, value in (("Width:", "96"), ("Height:", "72"), ("Rate hz:", "20")):
            page.get_by_label(label, exact=True).fill(value)
        page.get_by_role("button", name="Save", exact=True).click()
        expect(page.locator(".messagelist .success")).to_be_visible()
    page.goto(f"{url}/admin/studyplatform/study/{study.pk}/design/")
    page.locator('input[name="design"][value="ratings"]').check()
    page.locator('input[name="questions"]').check()  # the study's one question
    page.get_by_label("Attention checks").fill("0")
    page.get_by_role("button", name="Build the pages").click()
    expect(page.locator("#summary-pages")).to_have_text(str(len(spec["items"])))
    return study


def _upload(page, url: str, study: Study, spec: dict, tmp_path: Path) -> None:
    """Upload the filmed clips in one zip with its manifest, on the Uploaded clips page."""
    page.goto(f"{url}/admin/studyplatform/study/{study.pk}/uploads/")
    bundle = tmp_path / "films.zip"
    with zipfile.ZipFile(bundle, "w") as archive:
        rows = [f"{key},signer,{key}.mp4" for key, *_ in spec["items"]]
        archive.writestr("manifest.csv", "item,condition,file\n" + "\n".join(rows) + "\n")
        for key, *_ in spec["items"]:
            archive.writestr(f"{key}.mp4", make_video(size="160x120", seconds=1.2))
    page.locator('input[name="archive"]').set_input_files(bundle)
    page.get_by_role("button", name="Upload zip").click()
    expect(page.locator(".messagelist .success")).to_contain_text(
        f"{len(spec['items'])} clips uploaded"
    )


def _in_language(text: str, language: str, domain: str = "django") -> str:
    """Return *text* from the catalogue of *language* (djangojs: participate.js's)."""
    if domain == "djangojs":
        locale = translation.to_locale(language)
        return gettext.translation(domain, settings.LOCALE_PATHS[0], [locale]).gettext(text)
    with translation.override(language):
        return translation.gettext(text)


def _take(browser, url: str, study: Study, spec: dict) -> tuple[Participant, dict]:
    """Take the study in Chromium, checking each page speaks the study's language."""
    language = spec["language"]
    typed = {key: answer for key, _, _, answer, _ in spec["items"]}
    saved = _in_language("Answer saved.", language, "djangojs")
    assert saved != "Answer saved."  # the catalogue has it
    context = browser.new_context(bypass_csp=True, locale="en-US")  # the browser asks English
    answers = {}
    try:
        page = context.new_page()
        page.goto(f"{url}/s/{study.slug}/")
        assert page.evaluate("document.documentElement.lang") == language
        page.get_by_role(
            "button", name=_in_language("Continue (I agree to take part)", language)
        ).click()
        while True:
            page.wait_for_selector("#page-form.ready")
            assert page.evaluate("document.documentElement.lang") == language
            form = page.locator("#page-form")
            number, key = int(form.get_attribute("data-page")), form.get_attribute("data-trial")
            item = Trial.objects.get(study=study, key=key).item.key
            field = page.locator('[name="q-word"]')
            field.fill(typed[item])
            field.press("Tab")
            page.locator("#save-status").get_by_text(saved).wait_for()
            answers[item] = typed[item]
            if number == 1:
                SCREENSHOTS.mkdir(exist_ok=True)
                page.screenshot(path=SCREENSHOTS / f"participant-{language}.png")
            body = page.locator("main").inner_text()
            assert not [text for text in ENGLISH if text in body], body
            button = page.locator("#next-button")
            finishing = button.text_content().strip() == _in_language("Finish", language)
            button.click()
            if finishing:
                break
            page.wait_for_function(
                f"document.getElementById('page-form').dataset.page !== '{number}'"
            )
        page.get_by_text(_in_language("Thank you", language), exact=True).wait_for()
        assert page.evaluate("document.documentElement.lang") == language
    finally:
        close_context(context)
    return Participant.objects.filter(study=study).get(), answers


@pytest.mark.parametrize("spec", [TURKISH, PORTUGUESE], ids=["tr-tid", "pt-br-libras"])
def test_a_study_in_its_language_is_built_taken_and_scored_letter_by_letter(
    page, browser, live_server, alice, settings, tmp_path, renderable, spec
):
    settings.MEDIA_ROOT = tmp_path / "media"
    url = live_server.url
    uploaded = spec is TURKISH
    study = _build(page, url, spec, uploaded)
    if uploaded:
        _upload(page, url, study, spec, tmp_path)
    generate_and_open(page, url, study)
    participant, answers = _take(browser, url, study, spec)
    assert participant.is_finished
    assert answers == {key: typed for key, _, _, typed, _ in spec["items"]}

    archive = download_report(page, url, study)
    rows = list(csv.DictReader(io.StringIO(archive.read("report/intelligibility.csv").decode())))
    scored = {row["item"]: float(row["mean_accuracy"]) for row in rows}
    assert scored == {key: score for key, _, _, _, score in spec["items"]}
