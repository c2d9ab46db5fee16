"""Camera recordings are stored with a duration and a seek index (issue 35, point 9).

Chromium's MediaRecorder writes WebM as a live stream: no length, no cues, so served as
recorded Chromium gives its length as Infinity (the player shows 0:00) and it cannot be
indexed; the stored files were also all named camera.webm. Now a camera's WebM is
remuxed on upload (ffmpeg, frames copied) and, for ASL videos, named by its content; a
signed answer (test_signed_exports_browser.py) keeps its private random name and records
the stored file's SHA-256.
"""

import hashlib
import re

import pytest
from playwright.sync_api import expect

from studyplatform.actions import do_import_study
from studyplatform.demo import spine_study
from studyplatform.models import AslVideo

pytestmark = pytest.mark.django_db(transaction=True)

CUES = b"\x1c\x53\xbb\x6b"  # the Matroska Cues element: the seek index
# Load *url* in a video element; return its duration and whether a seek to 0.5 s lands.
PLAYS = """async url => {
  const video = document.createElement("video");
  video.muted = true; video.preload = "auto"; video.src = url;
  document.body.append(video);
  await new Promise(done => video.addEventListener("loadedmetadata", done, {once: true}));
  const duration = video.duration;
  video.currentTime = 0.5;
  await new Promise(done => video.addEventListener("seeked", done, {once: true}));
  return {duration: Number.isFinite(duration) ? duration : String(duration),
          at: video.currentTime, seekable: video.seekable.length};
}"""


def playable(page, url: str) -> None:
    """Assert that Chromium gives *url*'s video a length and seeks in it."""
    played = page.evaluate(PLAYS, url)
    # A whole-second length arrives from JavaScript as an int (a run recorded 2 s exactly);
    # an unknown length arrives as the string "Infinity" or "NaN".
    duration = played["duration"]
    assert isinstance(duration, (int, float)) and duration > 0.5, played
    assert abs(played["at"] - 0.5) < 0.2 and played["seekable"] == 1, played


def test_an_asl_video_recorded_in_the_admin_is_named_by_its_content_and_seeks(
    page, live_server, alice, settings, tmp_path
):
    settings.MEDIA_ROOT = tmp_path / "media"
    study = do_import_study(spine_study(), owner=alice).study
    page.goto(live_server.url + "/admin/login/?next=/admin/")
    page.get_by_label("Username").fill("alice")
    page.get_by_label("Password").fill("pw-alice")
    page.get_by_role("button", name="Log in").click()
    page.goto(f"{live_server.url}/admin/studyplatform/study/{study.pk}/asl/")
    row = page.locator("#asl-prompts tbody tr").first
    row.get_by_role("button", name="Record with camera").click()
    expect(row.get_by_role("button", name="Stop and save")).to_be_visible()
    page.wait_for_timeout(1500)
    row.get_by_role("button", name="Stop and save").click()
    page.wait_for_load_state("load")
    expect(page.locator("#asl-prompts tbody tr.signed")).to_have_count(1, timeout=30_000)
    video = AslVideo.objects.get()
    stored = video.video.open("rb").read()
    digest = hashlib.sha256(stored).hexdigest()
    assert re.fullmatch(rf"asl/{digest}(_\w+)?\.webm", video.video.name), video.video.name
    assert CUES in stored
    playable(page, page.locator("#asl-prompts tr.signed video[src]").get_attribute("src"))
