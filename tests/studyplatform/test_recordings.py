"""Test words carrying their recordings: upload, capture, the four conditions made from
them, the motion-capture condition's simulated label, and bad uploads.

Recordings here are the engine's simulated captures written as BVH and as .pose
landmarks (synthesis.timing.simulate), and one video rendered by the engine and captured
back with MediaPipe.
"""

import re
import shutil
from pathlib import Path

import numpy as np
import pytest
from django.core.files.uploadedfile import SimpleUploadedFile

from stimuli.clips import ClipError, render
from studyplatform.actions import (
    GenerateOptions,
    RecordingRejected,
    StudyImportError,
    do_attach_recording,
    do_delete_recordings,
    do_duplicate_study,
    do_generate_stimuli,
    do_import_study,
)
from studyplatform.lib.exchange import export_study
from studyplatform.lib.recordings import current_recording
from studyplatform.lib.stimuli import clip_spec
from studyplatform.models import Condition, Item, Recording, Stimulus, Trial
from synthesis.capture import format_pose, from_hand_motion
from synthesis.fingerspelling.spelling import spell
from synthesis.rigs.hand import HandModel
from synthesis.skeleton.bvh import format_bvh
from synthesis.techniques import ClipRequest
from synthesis.timing import simulate_recording
from tests.conftest import as_draft, tiny_webm

pytestmark = pytest.mark.django_db
SMALL = {"width": 64, "height": 48, "rate_hz": 20.0}


def _simulated(word: str, seed: int, rate_hz: float = 30.0):
    motion, truth = simulate_recording(word, np.random.default_rng(seed), rate_hz=rate_hz)
    return motion, truth


def _bvh(word: str, seed: int = 1) -> SimpleUploadedFile:
    motion, _ = _simulated(word, seed)
    return SimpleUploadedFile(f"{word}.bvh", format_bvh(motion).encode())


def _pose(word: str, seed: int = 1, rate_hz: float = 20.0) -> SimpleUploadedFile:
    _, truth = _simulated(word, seed, rate_hz)
    model = HandModel()
    dofs = spell(word, "right", rate_hz, truth, 250.0)
    return SimpleUploadedFile(f"{word}.pose", format_pose(from_hand_motion(model, dofs, rate_hz)))


def _attach(item, upload, capture, **options) -> Recording:
    with capture(execute=True):
        recording = do_attach_recording(item, upload, **options)
    recording.refresh_from_db()
    return recording


@pytest.fixture
def media(settings, tmp_path):
    """Return where recordings are kept: private storage, not the public media."""
    settings.MEDIA_ROOT = tmp_path / "media"
    return settings.SIGNSTUDY_PRIVATE_MEDIA_ROOT


def test_every_condition_retimes_the_words_recording(
    fingerspelling, media, tmp_path, renderable, django_capture_on_commit_callbacks
):
    item = fingerspelling.items.get(key="DAVID")
    recording = _attach(item, _pose("DAVID"), django_capture_on_commit_callbacks)
    assert recording.status == Recording.Status.READY, recording.error
    assert recording.motion.name == recording.upload.name  # a .pose is used as it is
    assert recording.quality["residual_mm_median"] < 2.0
    clips = {}
    for condition in fingerspelling.conditions.all():
        condition.parameters = {**condition.parameters, **SMALL}
        spec = clip_spec(condition, item)
        assert spec.parameters["source"] == "recording"
        assert spec.parameters["recording"] == recording.motion.path
        clips[condition.key] = render(spec, tmp_path / "clips")
    assert len({clip.sha256 for clip in clips.values()}) == 4
    # Motion capture is the recording as performed: its duration is the recording's.
    performed, _ = _simulated("DAVID", 1, 20.0)
    assert clips["mocap"].duration_ms == pytest.approx(1000 * performed.duration_s, abs=100)
    assert clips["constant"].duration_ms != clips["variable"].duration_ms


def test_the_stand_in_is_labelled_simulated_until_every_word_has_a_recording(
    fingerspelling, media, django_capture_on_commit_callbacks
):
    mocap = fingerspelling.conditions.get(key="mocap")
    assert mocap.is_simulated
    words = list(fingerspelling.items.filter(kind=Item.Kind.WORD))
    for number, item in enumerate(words):
        _attach(item, _bvh(item.text), django_capture_on_commit_callbacks)
        mocap.refresh_from_db()
        assert item.recordings.get().status == Recording.Status.READY, item.recordings.get().error
        assert mocap.is_simulated == (number < len(words) - 1)
    assert str(mocap) == "Motion capture"
    # Clips are now made from the recordings; removing one brings the label back.
    spec = clip_spec(mocap, words[0])
    assert spec.parameters["recording"].endswith(".bvh")
    do_delete_recordings(words[0].recordings.all())
    mocap.refresh_from_db()
    assert mocap.is_simulated and current_recording(words[0]) is None
    assert clip_spec(mocap, words[0]).parameters["source"] == "simulated"


def test_a_new_recording_replaces_the_old_only_once_it_is_ready(
    fingerspelling, media, django_capture_on_commit_callbacks
):
    item = fingerspelling.items.get(key="HEAVEN")
    first = _attach(item, _bvh("HEAVEN"), django_capture_on_commit_callbacks)
    # A BVH that parses but spells another word cannot be retimed: it fails, the first stays.
    wrong = _attach(item, _bvh("A"), django_capture_on_commit_callbacks)
    assert wrong.status == Recording.Status.FAILED and wrong.error
    assert current_recording(item) == first and first.upload.storage.exists(first.upload.name)
    second = _attach(item, _bvh("HEAVEN", seed=2), django_capture_on_commit_callbacks)
    assert current_recording(item) == second
    assert list(item.recordings.all()) == [second]
    assert not first.upload.storage.exists(first.upload.name)


@pytest.mark.parametrize(
    ("name", "data", "message"),
    [
        ("notes.txt", b"hello", "is not a recording"),
        ("HEAVEN.pose", b"\x00\x01 not a pose file", "HEAVEN.pose"),
        ("HEAVEN.bvh", b"HIERARCHY\nROOT", "HEAVEN.bvh"),
        ("HEAVEN.bvh", b"\xff\xfe\x00", "is not a recording"),
        ("HEAVEN.bvh", b"HIERARCHY\n\xff\xfe", "not a BVH text file"),
        ("HEAVEN.mp4", b"<html><script>alert(1)</script></html>", "judged by its content"),
    ],
)
def test_bad_uploads_are_named_and_store_nothing(fingerspelling, media, name, data, message):
    item = fingerspelling.items.get(key="HEAVEN")
    with pytest.raises(RecordingRejected, match=message):
        do_attach_recording(item, SimpleUploadedFile(name, data))
    assert not Recording.objects.exists()
    assert not (media / "recordings").exists() or not any((media / "recordings").iterdir())


def test_a_pose_file_without_hands_is_refused(fingerspelling, media):
    model = HandModel()
    recording = from_hand_motion(model, np.zeros((3, len(model.dofs))), 10)
    empty = format_pose(
        type(recording)(
            recording.fps,
            recording.components,
            recording.points,
            np.zeros_like(recording.confidence),
            10,
            10,
        )
    )
    with pytest.raises(RecordingRejected, match="no hand"):
        do_attach_recording(
            fingerspelling.items.get(key="HEAVEN"), SimpleUploadedFile("HEAVEN.pose", empty)
        )


def test_only_words_take_recordings(spine, media):
    sentence = spine.items.first()
    with pytest.raises(RecordingRejected, match="only fingerspelled words"):
        do_attach_recording(sentence, _bvh("A"))


def test_a_condition_on_each_words_recording_names_a_word_without_one(fingerspelling, media):
    as_draft(fingerspelling)
    condition = Condition(
        study=fingerspelling,
        key="captured",
        label="Captured",
        parameters={"source": "recording", "timing": "mocap"},
    )
    condition.full_clean()  # valid: each word's own recording is found when rendering
    condition.save()
    trial = Trial.objects.filter(block__study=fingerspelling, kind="pairwise").first()
    trial.condition_b = condition
    trial.save()
    with pytest.raises(ClipError, match=f"{trial.item.key} has no recording yet"):
        do_generate_stimuli(fingerspelling, GenerateOptions(enqueue=False))
    assert not Stimulus.objects.filter(condition=condition).exists()


def test_a_video_is_captured_into_landmarks_with_progress(
    fingerspelling, media, tmp_path, renderable, django_capture_on_commit_callbacks
):
    from synthesis.techniques import ClipRequest, render_request

    video = tmp_path / "AB.mp4"
    request = ClipRequest.from_parameters(
        "word",
        "AB",
        {"timing": "constant", "view": "hand", "width": 320, "height": 240, "rate_hz": 15.0},
    )
    render_request(request, video)
    item = Item.objects.create(study=fingerspelling, key="AB", text="AB")
    upload = SimpleUploadedFile("AB.mp4", video.read_bytes())
    recording = _attach(item, upload, django_capture_on_commit_callbacks, one_hand=True)
    assert recording.status == Recording.Status.READY, recording.error
    assert recording.motion.name.endswith(".pose") and recording.progress_percent == 100
    assert recording.sheet.name.endswith("-contact.png") and recording.sheet.size > 1000
    assert recording.quality["hands_found"]["right"] > 0.8
    assert (
        clip_spec(fingerspelling.conditions.get(key="mocap"), item)
        .parameters["recording"]
        .endswith(".pose")
    )


def test_the_recordings_page_uploads_and_reports_progress(
    client, alice, bob, fingerspelling, media, django_capture_on_commit_callbacks
):
    client.force_login(alice)
    url = f"/admin/studyplatform/study/{fingerspelling.pk}/recordings/"
    page = client.get(url)
    assert page.status_code == 200
    assert "0 of 9</strong> words have a recording" in page.text
    item = fingerspelling.items.get(key="HEAVEN")
    with django_capture_on_commit_callbacks(execute=True):
        saved = client.post(url, {"item": item.pk, "recording": _bvh("HEAVEN")})
    assert saved.status_code == 302
    response = client.get(url)
    assert "Recording of HEAVEN saved" in response.text
    assert "1 of 9</strong> words have a recording" in response.text
    progress = client.get(url + "progress.json").json()
    heaven = next(word for word in progress["words"] if word["key"] == "HEAVEN")
    assert heaven["used"]["status"] == "ready" and progress["capturing"] == 0
    # A bad file is named; a word of another study, or another researcher, is refused.
    bad = client.post(
        url, {"item": item.pk, "recording": SimpleUploadedFile("a.txt", b"x")}, follow=True
    )
    assert "Not saved: “a.txt” is not a recording" in bad.text
    client.force_login(bob)
    assert client.get(url).status_code == 404
    assert client.post(url, {"item": item.pk, "recording": _bvh("HEAVEN")}).status_code == 404
    assert Recording.objects.count() == 1


def test_a_video_captured_without_a_contact_sheet_keeps_its_landmarks(fingerspelling, media):
    """A worker without OpenGL captures but draws no sheet: clips still use the .pose."""
    from studyplatform.actions import do_finish_recording

    item = fingerspelling.items.get(key="HEAVEN")
    video = Recording(item=item)
    video.upload.save("HEAVEN.webm", SimpleUploadedFile("HEAVEN.webm", tiny_webm()), save=True)
    pose = _pose("HEAVEN").read()
    assert do_finish_recording(video, {"frames": 3}, pose=pose, sheet=None) == "ready"
    video.refresh_from_db()
    assert video.motion.name.endswith(".pose") and video.motion.read() == pose
    assert not video.sheet


def test_a_copied_study_keeps_its_words_recordings_and_shares_their_files(
    fingerspelling, media, alice, django_capture_on_commit_callbacks
):
    words = list(fingerspelling.items.filter(kind=Item.Kind.WORD))
    for item in words:
        _attach(item, _bvh(item.text), django_capture_on_commit_callbacks)
    exported = export_study(fingerspelling)
    assert [row["item"] for row in exported["recordings"]] == [w.key for w in words]
    with django_capture_on_commit_callbacks(execute=True):
        copy = do_duplicate_study(fingerspelling, owner=alice)
    assert not copy.conditions.get(key="mocap").is_simulated  # every word came with its own
    original, copied = (
        current_recording(words[0]),
        current_recording(copy.items.get(key=words[0].key)),
    )
    assert copied.pk != original.pk and copied.motion.name == original.motion.name
    assert copied.status == Recording.Status.READY
    # Deleting the original's recording keeps the file the copy still uses.
    with django_capture_on_commit_callbacks(execute=True):
        do_delete_recordings([original])
    assert (media / copied.motion.name).exists()
    assert clip_spec(copy.conditions.get(key="mocap"), copied.item).parameters["recording"] == (
        copied.motion.path
    )


def test_an_imported_recording_whose_file_is_missing_is_left_out_by_name(
    fingerspelling, media, alice, django_capture_on_commit_callbacks
):
    item = fingerspelling.items.get(key="DAVID")
    _attach(item, _bvh("DAVID"), django_capture_on_commit_callbacks)
    exported = export_study(fingerspelling)
    (media / exported["recordings"][0]["motion"]).unlink()
    result = do_import_study(exported, owner=alice, slug="elsewhere")
    assert result.warnings == (
        f"recordings[0]: upload file {exported['recordings'][0]['upload']!r} of DAVID is not in "
        "media; left out.",
    )
    assert not Recording.objects.filter(item__study=result.study).exists()
    assert result.study.conditions.get(key="mocap").is_simulated


@pytest.mark.parametrize(
    ("change", "message"),
    [
        (
            {"motion": "../settings.py"},
            "recordings[0].motion: '../settings.py' is not a recording's",
        ),
        ({"upload": "recordings/../../x.pose"}, "recordings[0].upload: 'recordings/../../x.pose'"),
        ({"item": "NOPE"}, "recordings[0].item: unknown item 'NOPE'"),
        ({"item": None}, "recordings[0].item: recordings belong to words; None is not one"),
    ],
)
def test_a_tampered_recording_in_a_definition_is_refused_by_name(
    fingerspelling, media, alice, django_capture_on_commit_callbacks, change, message
):
    item = fingerspelling.items.get(key="DAVID")
    _attach(item, _bvh("DAVID"), django_capture_on_commit_callbacks)
    exported = export_study(fingerspelling)
    exported["recordings"][0].update(change)
    with pytest.raises(StudyImportError, match=re.escape(message)):
        do_import_study(exported, owner=alice, slug="elsewhere")
    assert not fingerspelling.__class__.objects.filter(slug="elsewhere").exists()


@pytest.mark.skipif(shutil.which("assimp") is None, reason="assimp-utils is not installed")
def test_glb_and_fbx_motion_come_in_as_bvh(
    fingerspelling, django_capture_on_commit_callbacks, tmp_path
):
    # A word's motion exported by the engine as GLB comes back as a BVH recording; the
    # FBX of assimp's test models reads (through assimp) but its skeleton is no hand.
    from synthesis.interchange import request_glb

    item = fingerspelling.items.filter(kind=Item.Kind.WORD).first()
    request = ClipRequest.from_parameters("word", item.text, {"rate_hz": 30.0, "view": "hand"})
    glb = SimpleUploadedFile(f"{item.key}.glb", request_glb(request))
    recording = _attach(item, glb, django_capture_on_commit_callbacks)
    assert recording.status == Recording.Status.READY, recording.error
    assert recording.upload.name.endswith(".glb") and recording.motion.name.endswith(".bvh")
    assert recording.quality["frames"] > 10
    fbx = Path("/usr/share/assimp/models/FBX/animation_with_skeleton.fbx")
    if fbx.is_file():
        upload = SimpleUploadedFile("bones.fbx", fbx.read_bytes())
        failed = _attach(item, upload, django_capture_on_commit_callbacks)
        assert failed.status == Recording.Status.FAILED
        assert "Cannot map this skeleton's joints" in failed.error


def test_the_recordings_page_shows_what_reading_a_motion_file_warned(
    client, alice, fingerspelling, media, django_capture_on_commit_callbacks
):
    """Issue 54: a BVH with more frame lines than it declares reads, as assimp, Blender
    and bvhio read it, and the researcher sees the warning, as on the command line."""
    client.force_login(alice)
    url = f"/admin/studyplatform/study/{fingerspelling.pk}/recordings/"
    item = fingerspelling.items.get(key="HEAVEN")
    motion, _ = _simulated("HEAVEN", 1)
    text = format_bvh(motion)
    extra = text.rstrip("\n") + "\n" + text.rstrip("\n").rsplit("\n", 1)[-1] + "\n"
    upload = SimpleUploadedFile("HEAVEN.bvh", extra.encode())
    with django_capture_on_commit_callbacks(execute=True):
        assert client.post(url, {"item": item.pk, "recording": upload}).status_code == 302
    recording = Recording.objects.get()
    assert recording.status == Recording.Status.READY
    assert recording.quality["frames"] == motion.n_frames
    page = client.get(url).text
    assert f"above {motion.n_frames + 1} frame lines; the last 1 left out" in page
    assert "Warning:" in page


def test_a_motion_files_unmapped_signing_hand_is_a_warning():
    """CMU's 01_01.bvh (Debian's assimp-testmodels) names no finger joints: a recording
    made from it keeps the signing hand's fingers at rest, which the page must say."""
    from pathlib import Path

    from studyplatform.tasks import _mapping_warnings
    from synthesis.skeleton.bvh import read_bvh

    path = Path("/usr/share/assimp/models/BVH/01_01.bvh")
    if not path.is_file():
        pytest.skip("assimp-testmodels is not installed (scripts/bootstrap.sh installs it)")
    warned = _mapping_warnings(read_bvh(path), "right", path.name)
    assert len(warned) == 1 and "so at rest: right hand's fingers" in warned[0]
    assert _mapping_warnings(_simulated("HEAVEN", 1)[0], "right", "HEAVEN.bvh") == []
