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
import io
import zipfile
from pathlib import Path

import pytest
from playwright.sync_api import expect

from studyplatform.models import Condition, Study, Trial
from tests.studyplatform.taking import (
    download_report,
    film_small,
    generate_and_open,
    interface_text,
    save_study_page,
    sign_in_at,
    take_study,
)
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
    save_study_page(page)
    study = Study.objects.get(title=spec["title"])
    assert study.slug == spec["slug"], study.slug
    assert (study.language, study.manual_alphabet) == (spec["language"], spec["manual_alphabet"])
    if not uploaded:
        film_small(page, url, Condition.objects.get(study=study, key="signer"), 96, 72)
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


def _answer(study: Study, spec: dict):
    """Type each word's answer, checking the page speaks the study's language."""
    language = spec["language"]
    typed = {key: answer for key, _, _, answer, _ in spec["items"]}

    def answer(page, key: str, number: int) -> str:
        assert page.evaluate("document.documentElement.lang") == language
        item = Trial.objects.get(study=study, key=key).item.key
        field = page.locator('[name="q-word"]')
        field.fill(typed[item])
        field.press("Tab")
        page.locator("#save-status").get_by_text(
            interface_text("Answer saved.", language, "djangojs")
        ).wait_for()
        if number == 1:
            SCREENSHOTS.mkdir(exist_ok=True)
            page.screenshot(path=SCREENSHOTS / f"participant-{language}.png")
        body = page.locator("main").inner_text()
        assert not [text for text in ENGLISH if text in body], body
        return typed[item]

    return answer


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
    assert interface_text("Answer saved.", spec["language"], "djangojs") != "Answer saved."
    answer = _answer(study, spec)
    participant, answers = take_study(browser, url, study.slug, answer, spec["language"])
    assert participant.is_finished
    shown = {Trial.objects.get(study=study, key=k).item.key: v for k, v in answers.items()}
    assert shown == {key: typed for key, _, _, typed, _ in spec["items"]}

    archive = download_report(page, url, study)
    rows = list(csv.DictReader(io.StringIO(archive.read("report/intelligibility.csv").decode())))
    scored = {row["item"]: float(row["mean_accuracy"]) for row in rows}
    assert scored == {key: score for key, _, _, _, score in spec["items"]}
