"""Test the demo: seeding is idempotent, the studies match spec 02 and 03, pages are served."""

import re
import urllib.request
from collections import Counter
from http.cookiejar import CookieJar

import pytest
from django.core.management import call_command
from django.http import HttpRequest

from studyplatform.lib.stimuli import clip_spec
from studyplatform.models import Recording, Study

pytestmark = pytest.mark.django_db


@pytest.fixture
def seeded(settings, tmp_path, capsys):
    settings.VAR_DIR = tmp_path
    settings.MEDIA_ROOT = tmp_path / "media"
    call_command("seed_demo")
    return capsys.readouterr().out


def test_seed_prints_a_working_admin_login(seeded, client):
    username = re.search(r"Username:\s+(\S+)", seeded).group(1)
    password = re.search(r"Password:\s+(\S+)", seeded).group(1)
    # A request, as a real sign-in has: django-axes checks its address for lockouts.
    assert client.login(request=HttpRequest(), username=username, password=password)


def test_seeding_again_changes_nothing_and_prints_the_same_login(seeded, capsys):
    counts = Study.objects.count()
    call_command("seed_demo")
    again = capsys.readouterr().out
    assert Study.objects.count() == counts == 5
    assert Recording.objects.count() == 9  # the alphabet study's human letters, once
    assert re.search(r"Password:\s+(\S+)", again).group(1) == re.search(
        r"Password:\s+(\S+)", seeded
    ).group(1)


def test_fingerspelling_demo_is_the_spec_02_design(seeded):
    study = Study.objects.get(slug="fingerspelling-timing")
    assert study.conditions.count() == 4
    assert study.conditions.get(key="mocap").is_simulated
    comparisons = study.trials.filter(kind="pairwise", block__kind="trials")
    assert comparisons.count() == 48
    ordered = Counter((t.condition_a.key, t.condition_b.key) for t in comparisons)
    assert set(ordered.values()) == {4} and len(ordered) == 12
    cells = Counter(
        (t.item.key, frozenset((t.condition_a.key, t.condition_b.key))) for t in comparisons
    )
    assert len(cells) == 48 and set(cells.values()) == {1}
    # Seed 000 Fig. 5.2: "2 / 51": demographics, instructions, 48 comparisons, closing;
    # the demo adds a practice page and an attention check (identical clips, rated same).
    assert study.trials.count() == 53
    practice = study.trials.get(block__kind="practice")
    assert practice.item.is_practice and practice.condition_a != practice.condition_b
    check = study.trials.get(is_attention_check=True)
    assert check.block.key == "comparisons" and check.condition_a == check.condition_b
    assert check.expected_answer == "3"


def test_alphabet_demo_shows_each_letter_from_both_sources(seeded):
    study = Study.objects.get(slug="alphabet-legibility")
    trials = study.trials.filter(kind="intelligibility")
    assert Counter(t.condition_a.key for t in trials) == {"engine": 9, "human": 9}
    assert {t.item.key for t in trials} == set("ABCDLOSVY")
    # Every letter carries a real signer's recording (prepared by a job after commit).
    assert Recording.objects.filter(item__study=study).count() == 9
    assert not study.conditions.filter(is_simulated=True).exists()


def test_spine_demo_is_the_spec_03_design(seeded):
    study = Study.objects.get(slug="spine-motion")
    assert study.asl_first
    # Part 1 rates every sentence in both conditions, so its ratings compare them.
    ratings = study.trials.filter(kind="rating")
    assert Counter(t.condition_a.key for t in ratings) == {"spine-on": 5, "spine-off": 5}
    assert study.blocks.get(key="ratings").randomize_order
    assert study.trials.filter(kind="pairwise").count() == 5
    naturalness = study.questions.get(key="naturalness")
    labels = list(naturalness.options.values_list("label", flat=True))
    assert labels[0] == "Robotic" and labels[-1] == "Very human-like"


@pytest.mark.django_db(transaction=True)
def test_demo_serves_home_and_admin_over_http(live_server, settings, tmp_path, capsys):
    settings.VAR_DIR = tmp_path
    settings.MEDIA_ROOT = tmp_path / "media"
    call_command("seed_demo")
    password = re.search(r"Password:\s+(\S+)", capsys.readouterr().out).group(1)

    home = urllib.request.urlopen(live_server.url + "/")
    assert home.status == 200
    assert "Perceptual studies of sign-language animation" in home.read().decode()

    opener = urllib.request.build_opener(urllib.request.HTTPCookieProcessor(CookieJar()))
    login_page = opener.open(live_server.url + "/admin/login/").read().decode()
    token = re.search(r'name="csrfmiddlewaretoken" value="([^"]+)"', login_page).group(1)
    form = f"csrfmiddlewaretoken={token}&username=admin&password={password}&next=/admin/"
    request = urllib.request.Request(
        live_server.url + "/admin/login/",
        data=form.encode(),
        headers={"Referer": live_server.url + "/admin/login/"},
    )
    admin_index = opener.open(request)
    assert admin_index.status == 200
    assert admin_index.url.endswith("/admin/")
    studies = opener.open(live_server.url + "/admin/studyplatform/study/").read().decode()
    assert "ASL fingerspelling timing (demo)" in studies
    assert "Automated spine motion in ASL sentences (demo)" in studies
    # The alphabet study's human letters were captured (fitted) by the seeding's jobs.
    human = Study.objects.get(slug="alphabet-legibility").conditions.get(key="human")
    letter = human.study.items.get(key="B")
    assert letter.recordings.get().status == Recording.Status.READY
    assert clip_spec(human, letter).parameters["recording"].endswith(".pose")


def test_every_demo_asks_one_asl_fluency_scale():
    """Issue 35: three demos asked ASL fluency on three different scales."""
    from studyplatform.demo import DEMO_STUDIES
    from studyplatform.demo.common import ASL_FLUENCY

    scales = {}
    for build in DEMO_STUDIES:
        data = build()
        for question in data["questions"]:
            if question["key"] == "asl-fluency":
                scales[data["study"]["slug"]] = tuple(o["label"] for o in question["options"])
    assert len(scales) >= 4 and set(scales.values()) == {ASL_FLUENCY}, scales


def test_every_demo_sentence_turns_its_palms_as_its_signs_say():
    """Issue 36: every key of the demo's sign pairs and signed prompts within 30° of the
    palm its sign asks for, spine on and off (the story's: tests/synthesis/test_palms.py)."""
    from studyplatform.demo.signed import SPINE_PROMPTS
    from studyplatform.demo.transitions import SIGN_PAIRS
    from synthesis.signing.nonmanual import parse_spans
    from synthesis.signing.palms import key_misses

    for text in [text for _, text in SIGN_PAIRS] + [gloss for *_, gloss in SPINE_PROMPTS]:
        for spine in (True, False):
            worst = max(key_misses(parse_spans(text)[0], spine=spine), key=lambda e: e.angle_deg)
            assert worst.angle_deg <= 30.0, (text, spine, worst)
