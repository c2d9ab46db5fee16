"""Bring your own avatar in Chromium (issue 37): a researcher uploads a VRM on the Avatars
page, sees what the engine makes of it and its preview stills, and films a condition
with it. The screenshot is the researcher guide's."""

from pathlib import Path

import pytest
from playwright.sync_api import expect

from studyplatform.models import Avatar, Condition
from tests.conftest import as_draft
from tests.studyplatform.taking import sign_in_at
from tests.synthesis.humanoids import humanoid_glb

SCREENSHOTS = Path(__file__).resolve().parents[2] / "test-results"

pytestmark = pytest.mark.django_db(transaction=True)


def test_an_avatar_is_uploaded_previewed_and_films_a_condition(
    page, live_server, alice, fingerspelling, tmp_path, renderable
):
    url = live_server.url
    as_draft(fingerspelling)
    vrm = tmp_path / "tiny-signer.vrm"
    vrm.write_bytes(humanoid_glb(vrm=True, morphs=("browInnerUp", "jawOpen")))
    sign_in_at(page, url, "/admin/studyplatform/avatar/add/")
    page.get_by_label("GLB or VRM file").set_input_files(vrm)
    page.get_by_label("Licence").fill("CC0 (made by the test suite)")
    page.get_by_role("button", name="Save and continue editing").click()
    expect(page.locator(".messagelist .success")).to_be_visible(timeout=60_000)
    avatar = Avatar.objects.get()
    assert avatar.status == Avatar.Status.READY, avatar.error
    page.reload()
    expect(page.get_by_text("44 of 44 joints mapped")).to_be_visible()
    expect(page.get_by_text("plays 2 channels (browInnerUp, jawOpen)")).to_be_visible()
    page.wait_for_function(
        "[...document.querySelectorAll('.field-stills img')].length === 3 && "
        "[...document.querySelectorAll('.field-stills img')].every(i => i.naturalWidth > 0)"
    )
    SCREENSHOTS.mkdir(exist_ok=True)
    page.screenshot(path=SCREENSHOTS / "admin-avatar.png", full_page=True)
    condition = Condition.objects.filter(study=fingerspelling).first()
    page.goto(f"{url}/admin/studyplatform/condition/{condition.pk}/change/")
    page.locator("#id_avatar").select_option(str(avatar.pk))
    page.get_by_role("button", name="Save", exact=True).click()
    expect(page.locator(".messagelist .success")).to_be_visible()
    condition.refresh_from_db()
    assert condition.avatar == avatar
