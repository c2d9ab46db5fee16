"""Take a study in Chromium as a participant, page by page, answering as a test says."""

from collections.abc import Callable

from studyplatform.models import Participant
from tests.conftest import close_context


def filmed_small(definition: dict, width: int = 160, height: int = 120) -> dict:
    """Return a study definition whose conditions film small at 20 fps (quick to render)."""
    for condition in definition["conditions"]:
        condition["parameters"].update(width=width, height=height, rate_hz=20.0)
    return definition


def without_trials(definition: dict, leave_out) -> dict:
    """Return a study definition without the trials *leave_out(trial)* is true of (a shorter
    study to take in a test; what it still holds keeps its order)."""
    definition["trials"] = [t for t in definition["trials"] if not leave_out(t)]
    return definition


def interface_text(text: str, language: str, domain: str = "django") -> str:
    """Return the participant interface's *text* in *language* (djangojs: the catalogue
    participate.js speaks from)."""
    import gettext

    from django.conf import settings
    from django.utils import translation

    if domain == "djangojs":
        if language == "en":
            return text
        locale = translation.to_locale(language)
        return gettext.translation(domain, settings.LOCALE_PATHS[0], [locale]).gettext(text)
    with translation.override(language):
        return translation.gettext(text)


def take_study(
    browser, url: str, slug: str, answer: Callable, language: str = "en"
) -> tuple[Participant, dict]:
    """Take the study at /s/*slug*/ to its end; return the participant and the answers.

    *answer(page, trial_key, page_number)* fills the page's answers and returns what it
    chose (kept by trial key); the helper waits for "Answer saved." and goes on. The
    pages' buttons and messages are looked for in the study's *language*.
    """
    consent = interface_text("Continue (I agree to take part)", language)
    saved = interface_text("Answer saved.", language, "djangojs")
    finish = interface_text("Finish", language)
    context = browser.new_context(bypass_csp=True)
    answers = {}
    try:
        page = context.new_page()
        page.goto(f"{url}/s/{slug}/")
        page.get_by_role("button", name=consent).click()
        while True:
            page.wait_for_selector("#page-form.ready")
            form = page.locator("#page-form")
            number, key = int(form.get_attribute("data-page")), form.get_attribute("data-trial")
            answers[key] = answer(page, key, number)
            page.locator("#save-status").get_by_text(saved).wait_for()
            button = page.locator("#next-button")
            finishing = button.text_content().strip() == finish
            button.click()
            if finishing:
                break
            page.wait_for_function(
                f"document.getElementById('page-form').dataset.page !== '{number}'"
            )
        page.get_by_text(interface_text("Thank you", language), exact=True).wait_for()
    finally:
        close_context(context)
    return Participant.objects.filter(study__slug=slug).order_by("-pk").first(), answers


def save_study_page(page) -> None:
    """Save the admin page that is open, expecting no error and its success message."""
    from playwright.sync_api import expect

    page.get_by_role("button", name="Save and continue editing").click()
    page.wait_for_load_state("load")
    errors = page.locator(".errorlist, .errornote").all_text_contents()
    assert not errors, errors
    expect(page.locator(".messagelist .success")).to_be_visible()


def film_small(page, url: str, condition, width: int, height: int) -> None:
    """Set a condition's clip size (and 20 fps) on its admin page: quick to render."""
    from playwright.sync_api import expect

    page.goto(f"{url}/admin/studyplatform/condition/{condition.pk}/change/")
    for label, value in (("Width:", width), ("Height:", height), ("Rate hz:", 20)):
        page.get_by_label(label, exact=True).fill(str(value))
    page.get_by_role("button", name="Save", exact=True).click()
    expect(page.locator(".messagelist .success")).to_be_visible()


def sign_in_at(page, url: str, path: str) -> None:
    """Sign in as alice and land on *path*."""
    page.goto(f"{url}/admin/login/?next={path}")
    page.get_by_label("Username").fill("alice")
    page.get_by_label("Password").fill("pw-alice")
    page.get_by_role("button", name="Log in").click()


def generate_and_open(page, url: str, study) -> None:
    """Generate the study's clips from its admin page, wait for them, and open it."""
    from playwright.sync_api import expect

    page.goto(f"{url}/admin/studyplatform/study/{study.pk}/change/")
    page.get_by_role("link", name="Generate stimuli").first.click()
    page.get_by_role("button", name="Generate stimuli").click()
    expect(page.locator("#stimuli-percent")).to_have_text("100", timeout=300_000)
    expect(page.locator("#stimuli-failed")).to_have_text("0")
    page.goto(f"{url}/admin/studyplatform/study/{study.pk}/change/")
    page.locator("#id_status").select_option("open")
    page.get_by_role("button", name="Save and continue editing").click()
    expect(page.locator(".messagelist .success")).to_be_visible()


def download_report(page, url: str, study):
    """Open the study's results page and return its report zip (a ZipFile)."""
    import io
    import zipfile
    from pathlib import Path

    page.goto(f"{url}/admin/studyplatform/study/{study.pk}/change/")
    page.locator(".object-tools").get_by_role("link", name="Results").click()
    with page.expect_download() as download:
        page.get_by_role("link", name="report (zip)").click()
    return zipfile.ZipFile(io.BytesIO(Path(download.value.path()).read_bytes()))


def check_pair_wins(archive, study, participant, clicked: dict) -> dict:
    """Assert the report's pairs.csv counts, by condition label, the clips *participant*
    clicked (*clicked*: trial key → clip position); return its row."""
    import csv
    import io

    from studyplatform.lib import presented_conditions
    from studyplatform.models import Trial

    (pairs,) = list(csv.DictReader(io.StringIO(archive.read("report/pairs.csv").decode())))

    def name(condition) -> str:  # as the analysis names it
        return condition.label + (" (simulated)" if condition.simulated else "")

    wins = {name(c): 0 for c in study.conditions.all()}
    for key, position in clicked.items():
        trial = Trial.objects.get(study=study, key=key)
        wins[name(presented_conditions(participant, trial)[position - 1])] += 1
    assert {pairs["a"]: int(pairs["a_wins"]), pairs["b"]: int(pairs["b_wins"])} == wins
    return pairs
