"""The stimulus check in the platform: the command checks a study's clips, the Generate
page shows what it found, and nothing is refused.

Reference: the demo transitions study's first pair (WHERE SURPRISE) with the data-driven
Hermite join at 640×480, whose left elbow turns 2.9 × faster than keyed (measured) and
whose fists are under the size limit (issue 52: too small to read at 640×480).
"""

import pytest
from django.core.management import CommandError, call_command
from django.urls import reverse

from studyplatform.actions import do_import_study
from studyplatform.demo import transitions_study
from studyplatform.models import Trial

pytestmark = [pytest.mark.django_db, pytest.mark.slow]


@pytest.fixture
def first_pair(alice, settings, tmp_path):
    """The demo transitions study cut to its first item's pages, at 640×480 (the demo
    films at 1280×720 now, where its hands are large enough: no size warning)."""
    settings.MEDIA_ROOT = tmp_path
    definition = transitions_study()
    definition["study"].update(clip_width=640, clip_height=480)
    study = do_import_study(definition, owner=alice).study
    first = study.items.order_by("position").first()
    Trial.objects.filter(block__study=study).exclude(item=first).exclude(item=None).delete()
    return study


def test_the_command_checks_every_clip_and_the_generate_page_shows_the_warnings(
    first_pair, client, alice, capsys
):
    client.force_login(alice)
    url = reverse("admin:studyplatform_study_generate", args=[first_pair.pk])
    before = client.get(url).content.decode()
    assert "0 of 4 rendered clips checked" in before
    assert f"check_stimuli {first_pair.slug}" in before

    with pytest.raises(CommandError, match="warnings"):
        call_command("check_stimuli", first_pair.slug, "--strict")
    printed = capsys.readouterr().out
    assert f"{first_pair.slug}: 4 clips checked" in printed
    assert "hermite × P1: left_elbow turns at" in printed

    after = client.get(url).content.decode()
    assert "4 of 4 rendered clips checked" in after
    assert 'data-check="speed"' in after and "left_elbow turns at" in after
    assert 'data-check="size"' in after
    assert 'id="generate-form"' in after  # warnings refuse nothing
    progress = reverse("admin:studyplatform_study_stimuli", args=[first_pair.pk])
    assert "left_elbow turns at" in client.get(progress).content.decode()


def test_an_unknown_study_is_named():
    with pytest.raises(CommandError, match="No study with the slug nope"):
        call_command("check_stimuli", "nope")
