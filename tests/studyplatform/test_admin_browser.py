"""Take the researcher's first steps in real headless Chromium: sign in, open, preview."""

from pathlib import Path

import pytest
from playwright.sync_api import expect

from studyplatform.actions import do_import_study
from studyplatform.demo import fingerspelling_timing_study

SCREENSHOTS = Path(__file__).resolve().parents[2] / "test-results"

pytestmark = pytest.mark.django_db(transaction=True)


@pytest.fixture
def researcher(alice):
    do_import_study(fingerspelling_timing_study(), owner=alice)
    return alice


def test_researcher_signs_in_and_previews_the_demo(page, live_server, researcher):
    page.goto(live_server.url + "/")
    page.get_by_role("link", name="Sign in to the study admin").click()
    page.get_by_label("Username").fill("alice")
    page.get_by_label("Password").fill("pw-alice")
    page.get_by_role("button", name="Log in").click()
    page.get_by_role("link", name="Studies").first.click()
    page.get_by_role("link", name="ASL fingerspelling timing (demo)").click()
    expect(page.get_by_role("link", name="Preview")).to_be_visible()
    # The admin's own stylesheet is served, so the page is laid out, not bare HTML.
    assert page.locator("#header").evaluate("e => getComputedStyle(e).display") == "flex"
    page.get_by_role("link", name="Preview").click()
    # Assertions that wait: a click does not wait for the next page to load.
    expect(page.locator("section.preview-page")).to_have_count(55)
    expect(page.get_by_text("Page 53 of 53")).to_be_visible()
    # Clip slots keep their 4:3 box before any clip exists: no layout jump later.
    box = page.locator(".clip-slot").first.bounding_box()
    assert box["width"] > 100 and abs(box["width"] / box["height"] - 4 / 3) < 0.02
    SCREENSHOTS.mkdir(exist_ok=True)
    page.screenshot(path=SCREENSHOTS / "admin-preview.png")
    # The ASL videos page lists what participants read, none signed yet in this import.
    page.go_back()
    page.get_by_role("link", name="ASL videos").click()
    expect(page.locator("#asl-summary")).to_be_visible()
    # The summary shows before the long table is parsed: count rows once it all is.
    page.wait_for_load_state("load")
    rows = page.locator("#asl-prompts tbody tr")
    assert rows.count() > 10 and rows.count() == page.locator("tr.unsigned").count()
    assert page.locator("#asl-summary").text_content().strip().startswith(f"0 of {rows.count()}")
    page.screenshot(path=SCREENSHOTS / "admin-asl.png")


def test_import_form_reports_a_bad_file(page, live_server, researcher, tmp_path):
    bad = tmp_path / "bad.json"
    bad.write_text('{"format": "other"}')
    page.allowed_errors = [r"HTTP 400 .*/study/import/", r"status of 400"]  # refused, on purpose
    page.goto(live_server.url + "/admin/login/?next=/admin/studyplatform/study/import/")
    page.get_by_label("Username").fill("alice")
    page.get_by_label("Password").fill("pw-alice")
    page.get_by_role("button", name="Log in").click()
    page.get_by_label("Definition").set_input_files(str(bad))
    page.get_by_role("button", name="Import").click()
    expect(page.get_by_text("Not imported: Not a study definition")).to_be_visible()


def test_stimuli_page_shows_progress_live(
    page, live_server, researcher, settings, tmp_path, renderable
):
    """The progress bar follows clips as a worker renders them, and names a failure."""
    from studyplatform.actions.stimuli import GenerateOptions, do_generate_stimuli
    from studyplatform.models import Stimulus, Study, Trial
    from studyplatform.tasks import render_now

    settings.MEDIA_ROOT = tmp_path
    study = Study.objects.get(slug="fingerspelling-timing")
    Trial.objects.filter(block__study=study).exclude(key="cmp-01").delete()
    for condition in study.conditions.all():
        condition.parameters = {**condition.parameters, "width": 64, "height": 48, "rate_hz": 20}
        condition.save()
    result = do_generate_stimuli(
        study, GenerateOptions(enqueue=False)
    )  # recorded, waiting for a worker
    first, second = Stimulus.objects.filter(pk__in=result.stimulus_ids)
    second.parameters = {**second.parameters, "text": "GUITAR!"}  # cannot be spelled
    second.save()

    page.goto(
        live_server.url + f"/admin/login/?next=/admin/studyplatform/study/{study.pk}/stimuli/"
    )
    page.get_by_label("Username").fill("alice")
    page.get_by_label("Password").fill("pw-alice")
    page.get_by_role("button", name="Log in").click()
    assert page.locator("#stimuli-count").text_content() == "0 / 2"
    assert render_now(first.pk) == Stimulus.Status.READY, Stimulus.objects.get(pk=first.pk).error
    page.wait_for_function("document.getElementById('stimuli-count').textContent === '1 / 2'")
    assert page.locator("#stimuli-percent").text_content() == "50"
    assert render_now(second.pk) == Stimulus.Status.FAILED
    failure = page.locator("#stimuli-failures li")
    failure.wait_for()
    assert "GUITAR" in failure.text_content() and "!" in failure.text_content()
    assert page.locator("#stimuli-failed").text_content() == "1"


def test_a_word_is_recorded_with_the_camera_and_a_file_uploaded(
    page, live_server, researcher, settings, tmp_path
):
    """The camera recorder posts a real WebM (Chromium's synthetic camera: no hand in
    it, so its capture fails by name); a BVH file uploaded beside it is used."""
    import numpy as np

    from synthesis.skeleton.bvh import format_bvh
    from synthesis.timing import simulate_recording

    settings.MEDIA_ROOT = tmp_path / "media"
    study = researcher.studies.get(slug="fingerspelling-timing")
    page.goto(live_server.url + "/admin/login/?next=/admin/")
    page.get_by_label("Username").fill("alice")
    page.get_by_label("Password").fill("pw-alice")
    page.get_by_role("button", name="Log in").click()
    page.goto(f"{live_server.url}/admin/studyplatform/study/{study.pk}/")
    page.get_by_role("link", name="Recordings").click()
    expect(page.locator("#recordings-summary")).to_contain_text("0 of 9")
    row = page.locator("tr", has=page.get_by_role("rowheader", name="GUITAR"))
    row.get_by_role("button", name="Record with camera").click()
    expect(row.get_by_role("button", name="Stop and save")).to_be_visible()
    page.wait_for_timeout(1500)
    row.get_by_role("button", name="Stop and save").click()
    expect(row.locator(".errornote")).to_contain_text("no hand was found", timeout=60_000)
    # Named as it is in media, not by where the server keeps it.
    assert row.locator(".errornote").text_content().strip().startswith("recordings/")
    motion, _ = simulate_recording("HEAVEN", np.random.default_rng(1), rate_hz=30.0)
    bvh = tmp_path / "HEAVEN.bvh"
    bvh.write_text(format_bvh(motion))
    row = page.locator("tr", has=page.get_by_role("rowheader", name="HEAVEN"))
    row.get_by_label("File").set_input_files(str(bvh))
    row.get_by_role("button", name="Upload").click()
    expect(page.get_by_text("Recording of HEAVEN saved")).to_be_visible()
    expect(page.locator("#recordings-summary")).to_contain_text("1 of 9")
    page.screenshot(path=SCREENSHOTS / "admin-recordings.png")

    # Motion from other tools (issue 37): a word's glTF motion comes in (as BVH), and
    # an FBX goes in through assimp, its skeleton refused by name (it is no hand).
    from synthesis.interchange import request_glb
    from synthesis.techniques import ClipRequest

    words = [i.key for i in study.items.filter(kind="word") if i.key not in ("HEAVEN", "GUITAR")]
    glb = tmp_path / f"{words[0]}.glb"
    request = ClipRequest.from_parameters("word", words[0], {"rate_hz": 30.0, "view": "hand"})
    glb.write_bytes(request_glb(request))
    row = page.locator("tr", has=page.get_by_role("rowheader", name=words[0]))
    row.get_by_label("File").set_input_files(str(glb))
    row.get_by_role("button", name="Upload").click()
    expect(page.locator("#recordings-summary")).to_contain_text("2 of 9", timeout=60_000)
    fbx = Path("/usr/share/assimp/models/FBX/animation_with_skeleton.fbx")
    if fbx.is_file():
        row = page.locator("tr", has=page.get_by_role("rowheader", name=words[1]))
        row.get_by_label("File").set_input_files(str(fbx))
        row.get_by_role("button", name="Upload").click()
        expect(row.locator(".errornote")).to_contain_text(
            "Cannot map this skeleton", timeout=60_000
        )
    page.screenshot(path=SCREENSHOTS / "admin-recordings-motion.png", full_page=True)


@pytest.mark.parametrize("status", ["draft", "open"])
def test_the_study_page_fits_a_1400_px_window(browser, live_server, researcher, status):
    """Issue 20 measured 2,357 px: the inlines' JSON and text cells were too wide."""
    from studyplatform.models import Study
    from tests.conftest import close_context

    study = Study.objects.get(slug="fingerspelling-timing")
    Study.objects.filter(pk=study.pk).update(status=status)
    context = browser.new_context(viewport={"width": 1400, "height": 900}, bypass_csp=True)
    try:
        page = context.new_page()
        page.goto(
            f"{live_server.url}/admin/login/?next=/admin/studyplatform/study/{study.pk}/change/"
        )
        page.get_by_label("Username").fill("alice")
        page.get_by_label("Password").fill("pw-alice")
        page.get_by_role("button", name="Log in").click()
        page.locator("#study_form").wait_for()
        page.locator(".inline-group .collapse-toggle, details summary").all()
        width = page.evaluate("document.documentElement.scrollWidth")
        assert width <= 1400, width
    finally:
        close_context(context)
