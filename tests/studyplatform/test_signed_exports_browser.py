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
from tests.studyplatform.test_participate_browser import _with_clips, open_trial_page

pytestmark = pytest.mark.django_db(transaction=True)


def test_a_signed_answer_is_in_the_csv_and_the_everything_zip(
    page, live_server, spine, clips_dir, one_clip
):
    _with_clips(spine, one_clip, clips_dir)
    participant = open_trial_page(page, live_server, spine, "comments")
    page.get_by_role("button", name="Record a signed answer").click()
    page.get_by_text("Recording…").wait_for()
    page.wait_for_timeout(1500)
    page.get_by_role("button", name="Stop recording").click()
    page.get_by_text("Watch your recording").wait_for()
    page.get_by_role("button", name="Send this recording").click()
    expect(page.locator(".signed-status")).to_have_text(
        "Your signed answer is saved.", timeout=20000
    )
    response = Response.objects.get(participant=participant, question__key="comments")
    stored = response.video.open("rb").read()
    digest = hashlib.sha256(stored).hexdigest()
    assert response.video_sha256 == digest

    # The owner downloads the CSV and the zip from the results page.
    page.goto(f"{live_server.url}/admin/login/?next=/admin/studyplatform/study/{spine.pk}/results/")
    page.get_by_label("Username").fill("bob")
    page.get_by_label("Password").fill("pw-bob")
    page.get_by_role("button", name="Log in").click()
    expect(page.locator("#signed-size")).to_have_text(
        f"1 signed answer ({len(stored) / 1e6:.1f} MB)"
    )
    rows = list(csv.DictReader(io.StringIO(page.request.get(
        f"{live_server.url}/admin/studyplatform/study/{spine.pk}/results/responses.csv").text()
    )))  # fmt: skip
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
