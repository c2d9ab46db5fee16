"""Test researchers' own avatars (issue 37): a GLB/VRM upload checked, stored privately,
reported on (bones, fingers, face) with preview stills; its bone mapping saved in the
file; a condition filmed with it, its file in the clip's hash; bad files store nothing.

The humanoids are built by tests/synthesis/humanoids.py.
"""

from pathlib import Path

import pytest
from django.core.files.uploadedfile import SimpleUploadedFile
from django.urls import reverse

from stimuli import stored_quality
from studyplatform.actions import GenerateOptions, do_duplicate_study, do_generate_stimuli
from studyplatform.actions.avatars import AvatarRejected, do_map_avatar_bones, do_upload_avatar
from studyplatform.lib.stimuli import clip_spec, clips_folder
from studyplatform.models import Avatar, Condition, Stimulus
from studyplatform.tasks import render_now
from tests.conftest import as_draft
from tests.synthesis.humanoids import humanoid_glb

pytestmark = pytest.mark.django_db


def _upload(owner, data: bytes, capture, name: str = "tiny.glb", stills: bool = False) -> Avatar:
    with capture(execute=stills):  # the stills job runs when the upload commits
        avatar = do_upload_avatar(owner, SimpleUploadedFile(name, data), "", "CC0", "tests")
    avatar.refresh_from_db()
    return avatar


def test_an_uploaded_avatar_is_stored_reported_on_and_previewed(
    bob, settings, django_capture_on_commit_callbacks, renderable
):
    avatar = _upload(
        bob,
        humanoid_glb(vrm=True, morphs=("browInnerUp",)),
        django_capture_on_commit_callbacks,
        "tiny.vrm",
        stills=True,
    )
    assert avatar.status == Avatar.Status.READY, avatar.error
    assert avatar.name == "Tiny signer" and avatar.licence == "CC0"  # VRM meta's name
    assert avatar.file.name == f"avatars/{avatar.sha256}.glb"
    assert (Path(settings.SIGNSTUDY_PRIVATE_MEDIA_ROOT) / avatar.file.name).is_file()
    report = avatar.report
    assert len(report["mapped"]) == report["joints"] == 44 and not report["unmapped"]
    assert report["missing_fingers"] == {"right": [], "left": []} and avatar.fingerspells
    assert report["missing_body"] == [] and avatar.signs
    assert report["face_channels"] == ["browInnerUp"]
    for still in (avatar.still_rest, avatar.still_letter, avatar.still_face):
        assert still.read()[:8] == b"\x89PNG\r\n\x1a\n"


@pytest.mark.parametrize(
    ("data", "message"),
    [
        (humanoid_glb()[:-200], "truncated"),
        (humanoid_glb(skin=False), "has no skin"),
        (b"\x00\x00\x00\x18ftypmp42" + b"\x00" * 100, "not a GLB or VRM"),
    ],
)
def test_a_bad_avatar_file_is_refused_and_stores_nothing(bob, settings, data, message):
    with pytest.raises(AvatarRejected, match=message):
        do_upload_avatar(bob, SimpleUploadedFile("bad.glb", data), "Bad", "CC0")
    assert not Avatar.objects.exists()
    folder = Path(settings.SIGNSTUDY_PRIVATE_MEDIA_ROOT) / "avatars"
    assert not folder.exists() or not any(folder.iterdir())


def test_a_bone_mapping_is_saved_in_the_file(bob, django_capture_on_commit_callbacks):
    avatar = _upload(bob, humanoid_glb(), django_capture_on_commit_callbacks)
    first = avatar.sha256
    with django_capture_on_commit_callbacks(execute=False):
        do_map_avatar_bones(avatar, {"RightHandThumb1": ""})
    avatar.refresh_from_db()
    assert avatar.sha256 != first and avatar.bone_mapping == {"RightHandThumb1": ""}
    assert "RightHandThumb1" in avatar.report["unmapped"]
    assert avatar.report["missing_fingers"]["right"] == ["right_thumb_cmc"]
    assert not avatar.fingerspells
    with pytest.raises(AvatarRejected, match="no joint 'Tail'"):
        do_map_avatar_bones(avatar, {"Tail": "hips"})
    with pytest.raises(AvatarRejected, match="engine has no joint 'wing'"):
        do_map_avatar_bones(avatar, {"Head": "wing"})


def test_arms_the_mapping_misses_are_named_not_left_in_a_t_pose_silently(
    bob, client, django_capture_on_commit_callbacks
):
    """Issue 54: an avatar whose arm bones the engine could not map rendered "45 joints
    mapped" with both arms held out as modelled, and nothing said so."""
    avatar = _upload(bob, humanoid_glb(), django_capture_on_commit_callbacks)
    with django_capture_on_commit_callbacks(execute=False):
        do_map_avatar_bones(avatar, {"RightForeArm": "", "LeftArm": "", "LeftForeArm": ""})
    avatar.refresh_from_db()
    assert avatar.report["missing_body"] == ["right_elbow", "left_shoulder", "left_elbow"]
    assert not avatar.signs
    client.force_login(bob)
    page = client.get(reverse("admin:studyplatform_avatar_change", args=[avatar.pk]))
    assert "stay as the avatar was modelled" in page.content.decode()
    assert "right_elbow, left_shoulder, left_elbow" in page.content.decode()


def test_a_condition_filmed_with_an_avatar_renders_it_and_hashes_its_file(
    bob, spine, settings, tmp_path, django_capture_on_commit_callbacks, renderable
):
    settings.MEDIA_ROOT = tmp_path
    as_draft(spine)
    avatar = _upload(bob, humanoid_glb(), django_capture_on_commit_callbacks)
    condition = Condition.objects.get(study=spine, key="spine-off")
    condition.avatar = avatar
    condition.parameters = {**condition.parameters, "width": 96, "height": 72, "rate_hz": 10.0}
    condition.full_clean()
    condition.save()
    item = spine.items.get(key="S5")
    before = clip_spec(condition, item)
    assert before.parameters["avatar_file"] == avatar.file.path
    with django_capture_on_commit_callbacks(execute=False):
        do_map_avatar_bones(avatar, {"Head": ""})
    condition.refresh_from_db()
    assert clip_spec(condition, item).content_hash() != before.content_hash()
    do_generate_stimuli(spine, GenerateOptions(enqueue=False))
    stimulus = Stimulus.objects.get(condition=condition, item=item)
    status = render_now(stimulus.pk)
    assert status == Stimulus.Status.READY, Stimulus.objects.get(pk=stimulus.pk).error
    # The stimulus check ran on it too, and says what it could not measure: this
    # avatar's skin is owned by no hand joint of the engine's.
    quality = stored_quality(clips_folder(), clip_spec(condition, item).content_hash())
    assert [f.check for f in quality.findings] == ["size"]
    assert "hands was found" in quality.findings[0].message
    # A copy for its owner keeps the avatar; another researcher's copy films the signer.
    assert do_duplicate_study(spine, owner=bob).conditions.get(key="spine-off").avatar == avatar


def test_the_admin_lists_only_the_researchers_own_avatars(
    client, bob, alice, spine, django_capture_on_commit_callbacks
):
    as_draft(spine)
    avatar = _upload(bob, humanoid_glb(), django_capture_on_commit_callbacks)
    client.force_login(bob)
    page = client.get(f"/admin/studyplatform/avatar/{avatar.pk}/change/")
    assert page.status_code == 200 and "44 of 44 joints mapped" in page.text
    assert client.get(f"/private/{avatar.file.name}").status_code == 200
    condition = Condition.objects.get(study=spine, key="spine-on")
    form = client.get(f"/admin/studyplatform/condition/{condition.pk}/change/")
    assert f'value="{avatar.pk}"' in form.text
    client.force_login(alice)
    assert client.get(f"/admin/studyplatform/avatar/{avatar.pk}/change/").status_code == 302
    assert client.get(f"/private/{avatar.file.name}").status_code == 404


def test_the_admin_uploads_an_avatar_and_names_a_refusal(
    client, bob, django_capture_on_commit_callbacks
):
    client.force_login(bob)
    with django_capture_on_commit_callbacks(execute=False):
        response = client.post(
            "/admin/studyplatform/avatar/add/",
            {
                "upload": SimpleUploadedFile("mine.glb", humanoid_glb()),
                "name": "Mine",
                "licence": "CC0",
                "source": "",
            },
        )
    assert response.status_code == 302, response.content[:2000]
    assert Avatar.objects.get().name == "Mine"
    response = client.post(
        "/admin/studyplatform/avatar/add/",
        {
            "upload": SimpleUploadedFile("bad.glb", humanoid_glb(skin=False)),
            "name": "Bad",
            "licence": "CC0",
        },
    )
    assert response.status_code == 400 and "has no skin" in response.text  # the form again
    assert Avatar.objects.count() == 1
