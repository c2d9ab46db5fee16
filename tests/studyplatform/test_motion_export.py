"""Test the clip's motion out from the stimulus page and the command line (issue 37):
GLB with the avatar, face and camera, and BVH; uploaded videos have none."""

import json
import struct

import pytest
from django.core.management import call_command
from django.core.management.base import CommandError

from studyplatform.actions import GenerateOptions, do_generate_stimuli
from studyplatform.models import Condition, Stimulus
from tests.conftest import as_draft

pytestmark = pytest.mark.django_db


def _glb_json(data: bytes) -> dict:
    """Return a GLB's JSON chunk (glTF 2.0 §4.4)."""
    magic, version, _ = struct.unpack("<4sII", data[:12])
    assert (magic, version) == (b"glTF", 2)
    length, kind = struct.unpack("<I4s", data[12:20])
    assert kind == b"JSON"
    return json.loads(data[20 : 20 + length])


@pytest.fixture
def clip(spine):
    do_generate_stimuli(spine, GenerateOptions(enqueue=False))
    return Stimulus.objects.get(condition__key="spine-on", item__key="S4")


def test_the_stimulus_page_offers_the_clips_motion_as_glb_and_bvh(client, bob, alice, clip):
    client.force_login(bob)
    page = client.get(f"/admin/studyplatform/stimulus/{clip.pk}/change/")
    assert f"/admin/studyplatform/stimulus/{clip.pk}/motion.glb" in page.text
    response = client.get(f"/admin/studyplatform/stimulus/{clip.pk}/motion.glb")
    assert response.status_code == 200 and response["Content-Type"] == "model/gltf-binary"
    assert response["Content-Disposition"].endswith('.glb"')
    data = b"".join(response.streaming_content) if response.streaming else response.content
    document = _glb_json(data)
    ours = document["asset"]["extras"]["signstudy"]
    assert (ours["condition"], ours["item"], ours["clip"]) == ("spine-on", "S4", clip.content_hash)
    assert {n["name"] for n in document["nodes"]} >= {"hips", "head", "right_wrist"}
    assert document["animations"][0]["channels"] and document["cameras"]
    bvh = client.get(f"/admin/studyplatform/stimulus/{clip.pk}/motion.bvh")
    assert bvh.status_code == 200 and bvh.content.startswith(b"HIERARCHY")
    client.force_login(alice)  # another researcher's study: no such clip
    assert client.get(f"/admin/studyplatform/stimulus/{clip.pk}/motion.glb").status_code == 404


def test_an_uploaded_clip_has_no_motion_and_the_command_writes_one(
    client, bob, spine, clip, tmp_path
):
    as_draft(spine)
    Condition.objects.filter(key="spine-off").update(source="uploaded", parameters={})
    do_generate_stimuli(spine, GenerateOptions(enqueue=False))
    uploaded = Stimulus.objects.get(condition__key="spine-off", item__key="S4")
    client.force_login(bob)
    response = client.get(f"/admin/studyplatform/stimulus/{uploaded.pk}/motion.glb")
    assert response.status_code == 409 and b"uploaded video" in response.content
    out = tmp_path / "s4.bvh"
    call_command("export_motion", spine.slug, "spine-on", "S4", "--out", str(out))
    assert out.read_text().startswith("HIERARCHY")
    with pytest.raises(CommandError, match="uploaded video"):
        call_command("export_motion", spine.slug, "spine-off", "S4", "--out", str(out))
    with pytest.raises(CommandError, match="No such clip"):
        call_command("export_motion", spine.slug, "spine-on", "S9", "--out", str(out))
