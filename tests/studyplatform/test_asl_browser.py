"""Take an ASL-first study with signed prompts in Chromium (issue 20's acceptance).

The ASL video precedes each English text it signs, "Hide the written text" leaves no
English that has a signed version on screen (unsigned English stays), and the page
passes axe with English hidden.
"""

import pytest
from django.contrib.contenttypes.models import ContentType
from django.core.files.uploadedfile import SimpleUploadedFile

from studyplatform.actions import do_attach_asl_video, do_enroll_participant
from studyplatform.models import Question, SignedTemplate
from tests.conftest import tiny_webm
from tests.studyplatform.test_participate_browser import (
    SCREENSHOTS,
    _serious_violations,
    _wait_ready,
    _with_clips,
)

pytestmark = pytest.mark.django_db(transaction=True)

# Every English text with a signed version must come right after an ASL video, in
# document order: its figure (or the caption in it), or (for a caption) the figure it
# sits in.
UNPRECEDED = """() => {
  const seen = Array.from(document.querySelectorAll("figure.asl-prompt, .english"));
  return seen.filter((el, i) => el.matches(".english.signed") &&
    !(i > 0 && (seen[i - 1].closest("figure.asl-prompt") || el.closest("figure.asl-prompt"))))
    .map(el => el.textContent.trim());
}"""
# Signed English still taking up room on screen (visually hidden text is 1 px).
STILL_SHOWN = """() => Array.from(document.querySelectorAll(".english.signed"))
  .filter(el => { const r = el.getBoundingClientRect(); return r.width > 1 || r.height > 1; })
  .map(el => el.textContent.trim())"""


def _sign(study, obj, field_name: str) -> None:
    upload = SimpleUploadedFile("sign.webm", tiny_webm(), "video/webm")
    content_type = ContentType.objects.get_for_model(obj).pk
    do_attach_asl_video(study, content_type, obj.pk, field_name, upload)


@pytest.fixture
def signed_spine(spine, bob, clips_dir, one_clip):
    """The ASL-first spine demo with its consent, two rating questions and a scale signed."""
    assert spine.asl_first
    _with_clips(spine, one_clip, clips_dir)
    _sign(spine, spine, "consent_text")
    _sign(spine, spine, "description")
    for key in ("clarity", "naturalness"):
        question = Question.objects.get(study=spine, key=key)
        _sign(spine, question, "text")
    for option in Question.objects.get(study=spine, key="clarity").options.all():
        _sign(spine, option, "label")
    template = SignedTemplate.objects.create(
        owner=bob,
        kind=SignedTemplate.Kind.NEXT,
        name="Next (lab)",
        transcript="Next page",
        video=SimpleUploadedFile("next.webm", tiny_webm(), "video/webm"),
    )
    spine.signed_templates.add(template)
    return spine


def test_an_asl_first_page_signs_first_and_hides_only_signed_english(
    page, live_server, signed_spine
):
    page.goto(f"{live_server.url}/s/{signed_spine.slug}/")
    assert page.evaluate(UNPRECEDED) == []
    assert len(page.locator(".english.signed").all()) == 2  # description and consent
    participant = do_enroll_participant(signed_spine, consented=True)
    participant.reached = len(participant.schedule)
    participant.save()
    number = next(i for i, e in enumerate(participant.schedule, 1) if e["trial"] == "rate-s1")
    page.goto(f"{live_server.url}/p/{participant.token}/{number}/")
    _wait_ready(page)
    # Two questions and five scale points are signed: their videos come first. Only the
    # scale's two end points have English labels (likert5), the others just a number.
    assert page.evaluate(UNPRECEDED) == []
    assert len(page.locator(".english.signed").all()) == 2 + 2
    clarity = page.locator('fieldset[data-question="clarity"]')
    assert clarity.locator("label.choice figure.asl-prompt video").count() == 5
    assert page.locator(".asl-buttons").count() == 1  # the Next button's template
    SCREENSHOTS.mkdir(exist_ok=True)
    page.screenshot(path=SCREENSHOTS / "participant-asl-first.png", full_page=True)
    toggle = page.locator("#english-toggle")
    toggle.click()
    assert toggle.get_attribute("aria-pressed") == "true"
    assert page.evaluate(STILL_SHOWN) == []
    # Unsigned English stays: the grammaticality question has no ASL video.
    grammar = page.locator('fieldset[data-question="grammaticality"] legend')
    assert grammar.is_visible() and "grammatical" in grammar.text_content().lower()
    assert _serious_violations(page) == []
    SCREENSHOTS.mkdir(exist_ok=True)
    page.screenshot(path=SCREENSHOTS / "participant-asl-first-english-hidden.png", full_page=True)
    # Hiding is remembered on the next page, and offered only where something is signed.
    pretest = next(i for i, e in enumerate(participant.schedule, 1) if e["trial"] == "pretest")
    page.goto(f"{live_server.url}/p/{participant.token}/{pretest}/")
    _wait_ready(page)
    assert page.locator("#english-toggle").count() == 0
