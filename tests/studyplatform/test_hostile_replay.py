"""Replay issue 51's hostile files against a live server: each answers 4xx, in time.

Sent over loopback as the attack run sent them (raw HTTP through
tests/studyplatform/attack.py), on SQLite and, in the PostgreSQL run, on PostgreSQL:
the cyclic and 200,000-node glTFs within 5 s with the serving process's memory flat,
and every upload that answered ≥ 500 then (25 of them, by kind) now a 4xx naming it.
The file-parameter cases are in test_file_references.py.
"""

import json
import time

import pytest

from studyplatform.lib.exchange import export_study
from studyplatform.models import Avatar, Condition, Recording, UploadedClip
from tests.conftest import as_draft
from tests.hostile import (
    GLTF_CASES,
    corrupt_deflate_zip,
    encrypted_member_zip,
    with_animation,
    zip_of,
)
from tests.studyplatform.attack import Attacker
from tests.synthesis.humanoids import humanoid_glb

pytestmark = pytest.mark.django_db(transaction=True)

GOOD = humanoid_glb()
GOOD_VRM = humanoid_glb(vrm=True, morphs=("eyeBlinkLeft",), expressions={"blink": 0})
JSON = {"Accept": "application/json"}


def _rss_mb() -> float:
    with open("/proc/self/status") as status:
        line = next(line for line in status if line.startswith("VmRSS:"))
    return int(line.split()[1]) / 1024


@pytest.fixture
def bob_http(live_server, bob, settings, tmp_path):
    settings.MEDIA_ROOT = tmp_path / "media"
    researcher = Attacker(live_server.url)
    assert researcher.sign_in("bob", "pw-bob").status == 302
    return researcher


def _avatar(researcher: Attacker, data: bytes):
    researcher.get("/admin/studyplatform/avatar/add/")
    fields = {"name": "h", "licence": "CC0", "source": ""}
    return researcher.post_file("/admin/studyplatform/avatar/add/", fields, "upload", "h.vrm", data)


def _recording(researcher: Attacker, study, data: bytes, name: str = "h.glb"):
    word = study.items.filter(kind="word").first()
    url = f"/admin/studyplatform/study/{study.pk}/recordings/"
    researcher.get(url)
    return researcher.post_file(url, {"item": word.pk}, "recording", name, data, headers=JSON)


@pytest.mark.parametrize("case", sorted(c for c, v in GLTF_CASES.items() if "avatar" in v[2]))
def test_hostile_avatars_answer_400_in_time_with_flat_memory(case, bob_http):
    make, vrm, _ = GLTF_CASES[case]
    data = make(GOOD_VRM if vrm else GOOD)
    _avatar(bob_http, GOOD)  # the pages and the engine warmed once
    before, started = _rss_mb(), time.monotonic()
    answer = _avatar(bob_http, data)
    assert answer.status == 400, answer.text[:300]
    assert time.monotonic() - started < 5.0
    assert _rss_mb() - before < 50
    assert "Traceback" not in answer.text
    assert Avatar.objects.filter(name="h").count() == 1  # the warm-up's alone


MOTION_CASES = sorted(
    case
    for case, (_, _, readers) in GLTF_CASES.items()
    if "motion" in readers or case in ("parent cycle", "200,000-node chain")
)


@pytest.mark.parametrize("case", MOTION_CASES)
def test_hostile_motion_answers_400_in_time(case, bob_http, fingerspelling, bob):
    from studyplatform.actions import do_import_study
    from studyplatform.demo import fingerspelling_timing_study

    words = do_import_study(fingerspelling_timing_study(), owner=bob, slug="bob-words").study
    make, _, _ = GLTF_CASES[case]
    data = make(with_animation(GOOD, [0.0, 0.5, 1.0]))
    started = time.monotonic()
    answer = _recording(bob_http, words, data)
    assert answer.status == 400, answer.text[:300]
    assert time.monotonic() - started < 5.0
    assert not Recording.objects.filter(item__study=words).exists()


def _definition(spine) -> dict:
    definition = export_study(spine)
    definition["study"]["slug"] = "replayed"
    return definition


def test_the_listed_imports_answer_400(bob_http, spine):
    url = "/admin/studyplatform/study/import/"
    bob_http.get(url)
    definition = json.dumps(_definition(spine)).encode()
    for study in (-1, "x"):
        data = json.dumps({**_definition(spine), "study": study}).encode()
        answer = bob_http.post_file(url, {}, "definition", "d.json", data)
        assert answer.status == 400, (study, answer.text[:300])
    bundles = (
        encrypted_member_zip("study.json", definition),
        corrupt_deflate_zip("study.json", definition * 3),
    )
    for bundle in bundles:
        answer = bob_http.post_file(url, {}, "definition", "d.zip", bundle)
        assert answer.status == 400, answer.text[:300]


def test_the_listed_clip_zips_answer_400(bob_http, spine):
    as_draft(spine)
    Condition.objects.filter(study=spine, key="spine-off").update(source="uploaded", parameters={})
    url = f"/admin/studyplatform/study/{spine.pk}/uploads/"
    bob_http.get(url)
    manifest = b"item,condition,file\nS1,spine-off,a.mp4\n"
    for archive, words in (
        (zip_of({"manifest.csv": b"item,condition,file\n" + b"x" * 140_000 + b",a,b\n"}), "CSV"),
        (encrypted_member_zip("manifest.csv", manifest), "cannot be read"),
        (corrupt_deflate_zip("manifest.csv", manifest * 40), "cannot be read"),
    ):
        answer = bob_http.post_file(url, {}, "archive", "clips.zip", archive, headers=JSON)
        assert answer.status == 400, answer.text[:300]
        assert words in answer.json()["error"]
    assert not UploadedClip.objects.exists()
