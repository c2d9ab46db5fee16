"""A signed answer recorded in Chromium is in the CSV and the "everything" zip (issue 35, 3).

Before: the CSV row had empty text and nothing pointing to the video, and the zip had no
videos; the file was reachable only per response in the admin.
"""

import csv
import hashlib
import io
import zipfile

import pytest
from playwright.sync_api import expect

from studyplatform.models import Response
from tests.studyplatform.test_camera_webm_browser import CUES, playable
from tests.studyplatform.test_participate_browser import (
    _with_clips,
    open_trial_page,
    record_signed_answer,
)

pytestmark = pytest.mark.django_db(transaction=True)


def test_a_signed_answer_is_in_the_csv_and_the_everything_zip(
    page, live_server, spine, clips_dir, one_clip
):
    _with_clips(spine, one_clip, clips_dir)
    participant = open_trial_page(page, live_server, spine, "comments")
    record_signed_answer(page)
    page.get_by_role("button", name="Send this recording").click()
    expect(page.locator(".signed-status")).to_have_text(
        "Your signed answer is saved.", timeout=20000
    )
    response = Response.objects.get(participant=participant, question__key="comments")
    stored = response.video.open("rb").read()
    digest = hashlib.sha256(stored).hexdigest()
    assert response.video_sha256 == digest
    # Stored remuxed (issue 35, 9): its length and seek index, so the participant's
    # preview on coming back has a length (Infinity, shown 0:00, as recorded).
    assert CUES in stored and response.video.name.endswith(".webm")
    page.reload()
    page.wait_for_selector("#page-form.ready")
    playable(page, page.locator(".signed-preview").get_attribute("src"))

    # The owner downloads the CSV and the zip from the results page.
    page.goto(f"{live_server.url}/admin/login/?next=/admin/studyplatform/study/{spine.pk}/results/")
    page.get_by_label("Username").fill("bob")
    page.get_by_label("Password").fill("pw-bob")
    page.get_by_role("button", name="Log in").click()
    expect(page.locator("#signed-size")).to_have_text(
        f"1 signed answer ({len(stored) / 1e6:.1f} MB)"
    )
    rows = list(
        csv.DictReader(
            io.StringIO(
                page.request.get(
                    f"{live_server.url}/admin/studyplatform/study/{spine.pk}/results/responses.csv"
                ).text()
            )
        )
    )
    (row,) = [r for r in rows if r["question"] == "comments"]
    assert row["video_sha256"] == digest
    fetched = page.request.get(f"{live_server.url}{row['video_url']}")
    assert fetched.status == 200 and fetched.body() == stored
    with page.expect_download() as done:
        page.get_by_role("link", name="everything (zip)").click()
    archive = zipfile.ZipFile(done.value.path())
    assert archive.read(f"signed_answers/{digest}.webm") == stored
    inner = list(csv.DictReader(io.StringIO(archive.read("responses.csv").decode())))
    assert [r["video_sha256"] for r in inner if r["question"] == "comments"] == [digest]
    with page.expect_download() as done:
        page.get_by_role("link", name="everything without the videos").click()
    names = zipfile.ZipFile(done.value.path()).namelist()
    assert "responses.csv" in names and not any(n.startswith("signed_answers/") for n in names)
