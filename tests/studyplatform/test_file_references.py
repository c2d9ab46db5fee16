"""Replay issue 51's first case: a file parameter reads no server file and no one else's.

A hostile second researcher imported a definition whose condition set
``"recording": "<var>/secret_key"``, pressed Generate and read the key back in the motion
export's error; another researcher's private recording came out as a GLB the same way.
File parameters on the platform are now references to stored objects
(:mod:`studyplatform.rules.files`), checked on save and on import, and resolved only
when a clip is specified. Sent over loopback to a live server, on SQLite and PostgreSQL.
"""

import json

import numpy as np
import pytest
from django.conf import settings as django_settings
from django.core.files.uploadedfile import SimpleUploadedFile

from stimuli.clips import ClipError
from studyplatform.actions import do_attach_recording
from studyplatform.lib.exchange import export_study
from studyplatform.lib.stimuli import clip_spec
from studyplatform.models import Condition, Recording, Study
from studyplatform.rules.files import FILE_SOURCES, file_parameters
from synthesis.skeleton.bvh import BvhError, format_bvh, parse_bvh
from synthesis.timing import simulate_recording
from tests.studyplatform.attack import Attacker

pytestmark = pytest.mark.django_db(transaction=True)

IMPORT = "/admin/studyplatform/study/import/"
SECRET = "k3y-" + "s" * 46  # what a SECRET_KEY file holds: one line, no spaces


@pytest.fixture
def secret_file(tmp_path):
    path = tmp_path / "secret_key"
    path.write_text(SECRET)
    return path


def _ready_recording(item) -> Recording:
    """Return a ready BVH recording of *item* (a simulated capture, stored privately)."""
    motion, _ = simulate_recording(item.text, np.random.default_rng(1), rate_hz=30.0)
    upload = SimpleUploadedFile(f"{item.key}.bvh", format_bvh(motion).encode())
    recording = do_attach_recording(item, upload)
    Recording.objects.filter(pk=recording.pk).update(status="ready", motion=recording.upload.name)
    recording.refresh_from_db()
    return recording


def _definition(study, slug: str, parameters: dict) -> bytes:
    definition = export_study(study)
    definition["study"]["slug"] = slug
    definition["conditions"][0]["parameters"] = parameters
    return json.dumps(definition).encode()


def _import(researcher: Attacker, data: bytes):
    researcher.get(IMPORT)
    return researcher.post_file(IMPORT, {}, "definition", "d.json", data)


def test_a_path_in_a_file_parameter_is_refused_naming_it(
    live_server, fingerspelling, spine, bob, secret_file
):
    """The secret key, /proc/self/environ and a relative escape: each a 400 naming the
    parameter, and the file's content in no answer."""
    researcher = Attacker(live_server.url)
    assert researcher.sign_in("bob", "pw-bob").status == 302
    studies = Study.objects.count()
    values = [
        str(secret_file),
        "/proc/self/environ",
        "../../var/secret_key",
        "file:///etc/passwd",
        f"recording:1/../{secret_file}",
    ]
    for number, value in enumerate(values):
        parameters = {"source": "recording", "recording": value}
        answer = _import(researcher, _definition(spine, f"planted-{number}", parameters))
        assert answer.status == 400, (value, answer.status, answer.text[:400])
        assert "recording" in answer.text and "must name a stored file" in answer.text
        assert SECRET not in answer.text
    assert Study.objects.count() == studies


def test_every_engine_only_file_parameter_is_refused(live_server, spine, bob, secret_file):
    """Parameters with no stored kind (hand databases, transition databases, libraries,
    lexicons, timing models) take no value at all on the platform."""
    researcher = Attacker(live_server.url)
    assert researcher.sign_in("bob", "pw-bob").status == 302
    engine_only = sorted(set(file_parameters()) - set(FILE_SOURCES))
    assert {"hand_database", "transition_db", "library", "lexicon", "model"} <= set(engine_only)
    for name in engine_only:
        answer = _import(researcher, _definition(spine, f"x-{name}", {name: str(secret_file)}))
        assert answer.status == 400, (name, answer.text[:300])
        assert name in answer.text and "command line" in answer.text


def test_another_researchers_recording_cannot_be_named(
    live_server, fingerspelling, spine, bob, alice, media_root
):
    """Bob names alice's recording by reference and by its private path: both refused;
    alice names it and her clip is made from it."""
    word = fingerspelling.items.filter(kind="word").first()
    recording = _ready_recording(word)
    researcher = Attacker(live_server.url)
    assert researcher.sign_in("bob", "pw-bob").status == 302
    for number, value in enumerate([f"recording:{recording.pk}", recording.motion.path]):
        parameters = {"source": "recording", "recording": value}
        answer = _import(researcher, _definition(spine, f"stolen-{number}", parameters))
        assert answer.status == 400, (value, answer.text[:300])
    owner = Attacker(live_server.url)
    assert owner.sign_in("alice", "pw-alice").status == 302
    parameters = {"source": "recording", "recording": f"recording:{recording.pk}"}
    answer = _import(owner, _definition(fingerspelling, "own-recording", parameters))
    assert answer.status == 302, answer.text[:400]
    condition = Condition.objects.get(study__slug="own-recording", position=0)
    item = condition.study.items.get(key=word.key)
    spec = clip_spec(condition, item)
    assert spec.parameters["recording"] == recording.motion.path


def test_a_path_saved_before_the_rule_renders_nothing(fingerspelling, secret_file):
    """A condition stored with a path (before this rule, or written around it) fails its
    clip with a message that quotes neither the path's content nor the key."""
    condition = fingerspelling.conditions.first()
    Condition.objects.filter(pk=condition.pk).update(
        parameters={"source": "recording", "recording": str(secret_file)}
    )
    condition.refresh_from_db()
    with pytest.raises(ClipError, match="recording must name a stored file") as error:
        clip_spec(condition, fingerspelling.items.first())
    assert SECRET not in str(error.value)


def test_a_bvh_error_never_quotes_the_file():
    """The BVH reader names lines and the grammar's words, never what else a file holds."""
    head = "HIERARCHY\nROOT Hips\n{\nOFFSET 0 0 0\nCHANNELS 1 Xrotation\n}\nMOTION\n"
    texts = (
        SECRET,
        f"HIERARCHY\nROOT Hips\n{{\nOFFSET 0 0 {SECRET}\n}}\n",
        f"HIERARCHY\nROOT Hips\n{{\nOFFSET 0 0 0\nCHANNELS 1 {SECRET}\n}}\nMOTION\n",
        f"{head}Frames: 1\nFrame Time: {SECRET}\n0\n",
        f"{head}Frames: {SECRET}\nFrame Time: 0.1\n0\n",
        f"{head}Frames: 1\nFrame Time: 0.1\n{SECRET}\n",
    )
    for text in texts:
        with pytest.raises(BvhError) as error:
            parse_bvh(text, "f.bvh")
        assert SECRET not in str(error.value) and "s" * 20 not in str(error.value)


@pytest.fixture
def media_root(settings, tmp_path):
    settings.MEDIA_ROOT = tmp_path / "media"
    return django_settings.SIGNSTUDY_PRIVATE_MEDIA_ROOT
