"""The ASL-first demo shows signed prompts in Chromium (issue 35, point 6).

The spine demo's prompts are signed by the avatar when the demo is rendered
(studyplatform.demo.signed): real clips, labelled avatar-signed demo material under
each video in every language setting; "Hide the written text" hides only the text of
signed texts, and "English only" takes the videos away.
"""

import json

import pytest

from studyplatform.demo.signed import CREDIT, SPINE_PROMPTS, sign_prompts, transcript
from studyplatform.models import AslVideo
from tests.studyplatform.test_asl_browser import STILL_SHOWN, UNPRECEDED
from tests.studyplatform.test_participate_browser import (
    SCREENSHOTS,
    _wait_ready,
    _with_clips,
    open_trial_page,
)

pytestmark = pytest.mark.django_db(transaction=True)

# Each signed prompt's video, once its metadata is in: its length in seconds.
DURATIONS = """() => Promise.all(Array.from(document.querySelectorAll("figure.asl-prompt video"))
  .map(v => v.readyState >= 1 ? v.duration : new Promise(done =>
    v.addEventListener("loadedmetadata", () => done(v.duration), {once: true}))))"""
# The questions whose ASL video comes right before them.
SIGNED_QUESTIONS = """() => Array.from(document.querySelectorAll("fieldset.question"))
  .filter(f => f.previousElementSibling && f.previousElementSibling.matches("figure.asl-prompt"))
  .map(f => f.dataset.question)"""


def test_the_asl_first_demo_signs_its_prompts_and_hides_only_signed_english(
    page, live_server, spine, clips_dir, one_clip, renderable
):
    _with_clips(spine, one_clip, clips_dir)
    assert sign_prompts(spine) == len(SPINE_PROMPTS)
    assert sign_prompts(spine) == 0  # a second load finds them signed
    videos = list(AslVideo.objects.all())
    assert len(videos) == len(SPINE_PROMPTS)
    assert {v.credit for v in videos} == {CREDIT}
    assert {v.transcript for v in videos} == {transcript(gloss) for *_, gloss in SPINE_PROMPTS}
    assert "Gloss: S-T-O-R-Y LITTLE, ME INFORM-YOU. O-K?" in {v.transcript for v in videos}
    assert all(v.video.name.endswith(".mp4") and v.poster for v in videos)
    # Rendered clips, content-addressed in the clips folder like the stimuli.
    # Each clip's facts are <hash>.json (its stimulus check is <hash>.quality.json).
    facts = [
        json.loads(p.read_text())
        for p in (clips_dir / "stimuli").glob("*.json")
        if "." not in p.stem
    ]
    assert sum(1 for f in facts if f["width"] == 480) == len(SPINE_PROMPTS)

    page.goto(f"{live_server.url}/s/{spine.slug}/")
    assert page.evaluate(UNPRECEDED) == []
    assert page.locator("figure.asl-prompt video").count() == 1  # the consent text
    assert all(d > 1 for d in page.evaluate(DURATIONS))
    assert CREDIT in page.locator("figure.asl-prompt .asl-credit").inner_text()

    open_trial_page(page, live_server, spine, "rate-s1")
    assert page.evaluate(UNPRECEDED) == []
    assert page.evaluate(SIGNED_QUESTIONS) == ["clarity", "naturalness"]
    durations = page.evaluate(DURATIONS)
    assert len(durations) == 2 and all(d > 1 for d in durations)
    SCREENSHOTS.mkdir(exist_ok=True)
    page.screenshot(path=SCREENSHOTS / "participant-asl-demo.png", full_page=True)

    page.locator("#english-toggle").click()
    assert page.evaluate(STILL_SHOWN) == []
    # Unsigned English stays, and so does the label saying who signs the videos.
    for key in ("grammaticality", "understandability"):
        assert page.locator(f'fieldset[data-question="{key}"] legend').is_visible()
    credits = page.locator(".asl-credit")
    assert credits.count() == 2 and all(c.is_visible() for c in credits.all())

    page.get_by_role("button", name="Switch to written text only").click()
    _wait_ready(page)
    assert page.locator("figure.asl-prompt").count() == 0
    clarity = page.locator('fieldset[data-question="clarity"] legend')
    assert "clarity" in clarity.inner_text().lower() and clarity.is_visible()
