"""A study mixing uploaded clips with rendered ones, built and taken in Chromium (issue 37).

A researcher adds a study whose "filmed" condition takes uploaded videos beside the
engine's rendered condition, uploads one clip on the Uploaded clips page and the other
in a zip with a manifest, builds pairwise pages, generates, opens the study; a
participant takes it, both clips of every page playing in Chromium; the tidy CSV marks
the uploaded condition and each clip's SHA-256, and the report analyses both conditions.
The screenshots are the researcher guide's.
"""

import csv
import io
import zipfile
from pathlib import Path

import pytest
from playwright.sync_api import expect

from studyplatform.models import Condition, Stimulus, Study, Trial, UploadedClip
from tests.studyplatform.taking import (
    check_pair_wins,
    download_report,
    film_small,
    generate_and_open,
    save_study_page,
    take_study,
)
from tests.studyplatform.test_uploaded_clips import make_video

SCREENSHOTS = Path(__file__).resolve().parents[2] / "test-results"

pytestmark = pytest.mark.django_db(transaction=True)


def _build(page, url: str) -> Study:
    """Add the study, its two conditions (one uploaded) and two words, in the admin."""
    page.goto(f"{url}/admin/login/?next=/admin/studyplatform/study/add/")
    page.get_by_label("Username").fill("alice")
    page.get_by_label("Password").fill("pw-alice")
    page.get_by_role("button", name="Log in").click()
    page.get_by_label("Title").fill("Filmed vs rendered")
    for index, (key, label) in enumerate((("avatar", "Avatar"), ("filmed", "Filmed signer"))):
        page.get_by_role("button", name="Add another Condition").click()
        page.locator(f'[name="conditions-{index}-key"]').fill(key)
        page.locator(f'[name="conditions-{index}-label"]').fill(label)
    page.locator('[name="conditions-1-source"]').select_option("uploaded")
    for index, word in enumerate(("CAT", "DOG")):
        page.get_by_role("button", name="Add another Item").click()
        page.locator(f'[name="items-{index}-key"]').fill(word)
        page.locator(f'[name="items-{index}-text"]').fill(word)
    save_study_page(page)
    study = Study.objects.get(title="Filmed vs rendered")
    assert Condition.objects.get(study=study, key="filmed").source == "uploaded"
    # The rendered condition films as small as the uploads, quick to render.
    film_small(page, url, Condition.objects.get(study=study, key="avatar"), 160, 120)
    page.goto(f"{url}/admin/studyplatform/study/{study.pk}/design/")
    page.get_by_label("Attention checks").fill("0")
    page.get_by_role("button", name="Build the pages").click()
    expect(page.locator("#summary-pages")).to_have_text("2")
    return study


def _upload(page, url: str, study: Study, tmp_path: Path) -> None:
    """Upload CAT's clip on its own (a MOV, converted) and DOG's in a zip."""
    page.goto(f"{url}/admin/studyplatform/study/{study.pk}/change/")
    page.locator(".object-tools").get_by_role("link", name="Uploaded clips").click()
    expect(page.locator("#upload-clips td.missing")).to_have_count(2)
    cat = tmp_path / "CAT filmed.mov"
    cat.write_bytes(make_video("mpeg4", size="160x120", container="mov", seconds=1.6))
    row = page.locator('#upload-clips tr[data-item="CAT"]')
    row.locator('input[name="clip"]').set_input_files(cat)
    row.get_by_role("button", name="Upload").click()
    expect(page.locator(".messagelist .success")).to_contain_text("converted to H.264")
    bundle = tmp_path / "clips.zip"
    with zipfile.ZipFile(bundle, "w") as archive:
        archive.writestr("manifest.csv", "item,condition,file\nDOG,filmed,films/dog.mp4\n")
        archive.writestr("films/dog.mp4", make_video(size="160x120", seconds=1.2))
    page.locator('input[name="archive"]').set_input_files(bundle)
    page.get_by_role("button", name="Upload zip").click()
    expect(page.locator(".messagelist .success")).to_contain_text("1 clip uploaded")
    expect(page.locator("#upload-clips td.uploaded")).to_have_count(2)
    # The researcher's preview plays the stored clip (private until the study opens).
    page.wait_for_function(
        "[...document.querySelectorAll('#upload-clips video')].every(v => v.readyState >= 1"
        " && v.videoWidth === 160)"
    )
    SCREENSHOTS.mkdir(exist_ok=True)
    page.screenshot(path=SCREENSHOTS / "admin-uploaded-clips.png", full_page=True)


def test_a_study_mixing_uploaded_and_rendered_clips_is_built_taken_and_analysed(
    page, browser, live_server, alice, settings, tmp_path, renderable
):
    settings.MEDIA_ROOT = tmp_path / "media"
    url = live_server.url
    study = _build(page, url)
    _upload(page, url, study, tmp_path)
    clip = UploadedClip.objects.get(item__key="CAT")
    # Before the study opens, its uploaded clips are nobody's but its researchers'.
    outsider = browser.new_context()
    assert outsider.request.get(f"{url}/clips/{clip.video.name}").status == 404
    generate_and_open(page, url, study)
    assert outsider.request.get(f"{url}/clips/{clip.video.name}").status == 200
    outsider.close()
    assert set(
        Stimulus.objects.filter(condition__study=study).values_list("status", flat=True)
    ) == {"ready"}

    # Motion out: the rendered clip's page offers what participants saw as GLB and BVH.
    rendered = Stimulus.objects.get(condition__key="avatar", item__key="CAT")
    page.goto(f"{url}/admin/studyplatform/stimulus/{rendered.pk}/change/")
    with page.expect_download() as download:
        page.get_by_role("link", name="GLB: avatar, motion, face and camera").click()
    glb = Path(download.value.path()).read_bytes()
    assert glb[:4] == b"glTF" and download.value.suggested_filename.endswith(".glb")
    page.screenshot(path=SCREENSHOTS / "admin-stimulus-motion.png")

    sources = {}

    def answer(page, key: str, number: int) -> int:
        # Both clips of the page load and play in Chromium, the uploaded one too.
        page.wait_for_function(
            "[...document.querySelectorAll('video.stimulus')].length === 2 && "
            "[...document.querySelectorAll('video.stimulus')].every(v => v.readyState >= 2)"
        )
        sources[key] = page.eval_on_selector_all("video.stimulus", "vs => vs.map(v => v.src)")
        if number == 1:
            page.screenshot(path=SCREENSHOTS / "participant-uploaded-pair.png")
        page.locator('input[name="q-more-natural"][value="2"]').check()
        return 2

    participant, clicked = take_study(browser, url, study.slug, answer)
    assert participant.is_finished and len(clicked) == 2
    assert all(any("/clips/uploads/" in src for src in srcs) for srcs in sources.values())

    # The tidy CSV says which clip came from where, and the file participants were sent.
    response = page.request.get(f"{url}/admin/studyplatform/study/{study.pk}/results/responses.csv")
    rows = list(csv.DictReader(io.StringIO(response.text())))
    assert len(rows) == 2
    for row in rows:
        trial = Trial.objects.get(study=study, key=row["trial"])
        for column, number in (("condition_a", 1), ("condition_b", 2)):
            condition = Condition.objects.get(study=study, key=row[column])
            assert row[f"{column}_source"] == condition.source
            stimulus = Stimulus.objects.get(condition=condition, item=trial.item)
            assert row[f"clip{number}_sha256"] == stimulus.sha256 != ""
            if condition.source == "uploaded":
                assert (
                    stimulus.sha256
                    == UploadedClip.objects.get(condition=condition, item=trial.item).sha256
                )

    # The report analyses both conditions and says which clips were uploaded.
    archive = download_report(page, url, study)
    check_pair_wins(archive, study, participant, clicked)
    report = archive.read("report/report.html").decode()
    assert "Uploaded clips:" in report and "Filmed signer" in report
