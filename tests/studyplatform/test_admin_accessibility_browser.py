"""axe-core on the admin pages a researcher uses (issue 55, item 8).

Study list, study page, design builder, uploads, results, ASL videos, generate and the
participants' list, at 1366×768, with the demo studies loaded and a participant's
answers in. Reference: axe-core 4.x (bundled by axe-playwright-python), WCAG 2.x A/AA
and best-practice rules; every violation counts, whatever its impact.
"""

import pytest
from django.urls import reverse

pytestmark = pytest.mark.django_db(transaction=True)


def _violations(page) -> list[str]:
    from axe_playwright_python.sync_playwright import Axe

    results = Axe().run(page)
    return [
        f"{v['id']} ({v['impact']}): {v['help']} — {[n['target'] for n in v['nodes']][:4]}"
        for v in results.response["violations"]
    ]


def test_the_researchers_admin_pages_pass_an_accessibility_scan(
    page, live_server, alice, fingerspelling, spine
):
    from studyplatform.models import Study

    Study.objects.filter(pk=spine.pk).update(owner=alice)  # an ASL-first study of hers
    page.set_viewport_size({"width": 1366, "height": 768})
    page.goto(f"{live_server.url}/admin/login/")
    page.get_by_label("Username").fill("alice")
    page.get_by_label("Password").fill("pw-alice")
    page.get_by_role("button", name="Log in").click()
    page.wait_for_url("**/admin/")
    pages = {
        "admin index": reverse("admin:index"),
        "study list": reverse("admin:studyplatform_study_changelist"),
    }
    for study in (fingerspelling, spine):
        for name in ("change", "design", "uploads", "results", "asl", "generate"):
            pages[f"{name} ({study.slug})"] = reverse(
                f"admin:studyplatform_study_{name}", args=[study.pk]
            )
    found = {}
    for name, url in pages.items():
        page.goto(live_server.url + url)
        page.wait_for_load_state("load")
        found[name] = _violations(page)
    failing = {name: v for name, v in found.items() if v}
    assert failing == {}, "\n".join(f"{name}: {v}" for name, v in failing.items())
