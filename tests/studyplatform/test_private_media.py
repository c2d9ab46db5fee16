"""Personal files are private; public media are served with byte ranges and caching."""

import os
import time

import pytest
from django.core.management import call_command
from django.test import Client
from django.urls import reverse
from django.utils import timezone

from studyplatform.actions.uploads import do_remove_abandoned_uploads, partial_directory
from studyplatform.models import Response
from tests.studyplatform.test_participate import WEBM, _chunk


@pytest.fixture
def signed(client, at_comments):
    """A spine participant's saved signed answer (the study is bob's)."""
    participant, number = at_comments
    assert _chunk(client, participant, number, WEBM, 0, final=True).json()["saved"]
    return Response.objects.get(participant=participant)


def _as(user) -> Client:
    browser = Client()
    browser.force_login(user)
    return browser


def test_a_signed_answer_is_not_public_media(client, signed, settings):
    name = signed.video.name
    assert not (settings.MEDIA_ROOT / name).exists()
    assert (settings.SIGNSTUDY_PRIVATE_MEDIA_ROOT / name).is_file()
    assert Client().get(f"/media/{name}").status_code == 404
    assert len(name.rsplit("-", 1)[1].split(".")[0]) == 32  # 128 random bits in the name


def test_only_the_studys_researchers_open_a_signed_answer(signed, bob, alice, django_user_model):
    url = signed.video.url
    assert url.startswith("/private/")
    assert Client().get(url).status_code == 404  # anonymous
    assert _as(alice).get(url).status_code == 404  # another researcher's study
    owner = _as(bob).get(url)
    stored = signed.video.open("rb").read()  # the upload remuxed: the same frames
    assert owner.status_code == 200 and b"".join(owner.streaming_content) == stored
    assert owner["Cache-Control"] == "private, no-store"
    ranged = _as(bob).get(url, headers={"Range": "bytes=0-3"})
    assert ranged.status_code == 206 and ranged["Content-Range"] == f"bytes 0-3/{len(stored)}"
    assert b"".join(ranged.streaming_content) == stored[:4]
    admin = django_user_model.objects.create_superuser("root", password="pw")
    assert _as(admin).get(url).status_code == 200


def test_the_participant_plays_back_their_own_answer_only_while_taking_part(client, signed):
    participant = signed.participant
    page = client.get(reverse("participant_page", args=[participant.token, _page_of(signed)]))
    url = reverse("participant_answer_video", args=[participant.token, signed.pk])
    assert url in page.text and signed.video.name not in page.text
    assert client.get(url, headers={"Range": "bytes=-2"}).status_code == 206
    assert Client().get(url.replace(participant.token, "x" * 43)).status_code == 404
    participant.finished_at = timezone.now()
    participant.save()
    assert client.get(url).status_code == 404


def _page_of(response) -> int:
    keys = [entry["trial"] for entry in response.participant.schedule]
    return keys.index(response.trial.key) + 1


def test_an_unfinished_upload_is_private_and_cleaned_when_abandoned(client, at_comments, bob):
    participant, number = at_comments
    _chunk(client, participant, number, WEBM[:100], 0)
    (part,) = partial_directory().glob("*.part")
    assert str(part).startswith(str(partial_directory()))
    assert _as(bob).get(f"/private/answers/partial/{part.name}").status_code == 404
    assert Client().get(f"/media/answers/partial/{part.name}").status_code == 404
    assert do_remove_abandoned_uploads(24) == []  # just written
    hours_ago = time.time() - 25 * 3600
    os.utime(part, (hours_ago, hours_ago))
    call_command("clean_uploads")
    assert not part.exists()
    with pytest.raises(ValueError, match="must be positive"):
        do_remove_abandoned_uploads(0)


def test_a_checked_private_download_can_be_left_to_the_web_server(signed, bob, settings):
    settings.SIGNSTUDY_SENDFILE_HEADER = "X-Accel-Redirect"
    handed = _as(bob).get(signed.video.url)
    assert handed["X-Accel-Redirect"] == f"/protected/{signed.video.name}"
    assert handed.content == b""
    settings.SIGNSTUDY_SENDFILE_HEADER = "X-Sendfile"
    assert _as(bob).get(signed.video.url)["X-Sendfile"] == signed.video.path


@pytest.fixture
def clip(settings, tmp_path):
    settings.MEDIA_ROOT = tmp_path
    (tmp_path / "stimuli").mkdir()
    (tmp_path / "asl").mkdir()
    (tmp_path / "asl" / "welcome.mp4").write_bytes(b"asl")
    path = tmp_path / "stimuli" / "abc.mp4"
    path.write_bytes(bytes(range(100)))
    return "/media/stimuli/abc.mp4"


@pytest.mark.parametrize(
    ("header", "status", "content_range", "body"),
    [
        ("bytes=0-1", 206, "bytes 0-1/100", bytes([0, 1])),
        ("bytes=98-", 206, "bytes 98-99/100", bytes([98, 99])),
        ("bytes=-3", 206, "bytes 97-99/100", bytes([97, 98, 99])),
        ("bytes=90-500", 206, "bytes 90-99/100", bytes(range(90, 100))),
        ("bytes=0-1,5-6", 200, None, bytes(range(100))),  # several ranges: the whole file
        ("bytes=100-", 416, "bytes */100", b""),
        ("bytes=-0", 416, "bytes */100", b""),
    ],
)
def test_public_media_answer_byte_ranges(client, clip, header, status, content_range, body):
    response = client.get(clip, headers={"Range": header})
    assert response.status_code == status and response["Accept-Ranges"] == "bytes"
    assert response.get("Content-Range") == content_range
    content = b"".join(response.streaming_content) if response.streaming else response.content
    assert content == body


def test_public_media_are_cached_and_revalidated(client, clip):
    whole = client.get(clip)
    assert whole["Cache-Control"] == "public, max-age=31536000, immutable"  # content-hashed
    assert whole["Content-Type"] == "video/mp4" and whole["Content-Length"] == "100"
    again = client.get(clip, headers={"If-None-Match": whole["ETag"]})
    assert again.status_code == 304
    stale = client.get(clip, headers={"Range": "bytes=0-1", "If-Range": '"other"'})
    assert stale.status_code == 200  # the file changed since: send it whole
    assert client.get("/media/asl/welcome.mp4")["Cache-Control"] == "public, max-age=86400"
    assert client.head(clip)["Content-Length"] == "100"
    assert client.get("/media/../secret_key").status_code == 404
    assert client.get("/media/stimuli/nothing.mp4").status_code == 404
    assert client.post(clip).status_code == 405


def test_the_migration_moves_existing_answers_out_of_public_media(signed, settings):
    from importlib import import_module

    from django.apps import apps

    name = signed.video.name
    stored = signed.video.open("rb").read()
    public = settings.MEDIA_ROOT / name
    public.parent.mkdir(parents=True, exist_ok=True)
    (settings.SIGNSTUDY_PRIVATE_MEDIA_ROOT / name).replace(public)  # as before the change
    (settings.MEDIA_ROOT / "answers" / "partial").mkdir()
    migration = import_module("studyplatform.migrations.0008_private_media")
    migration.move_personal_files(apps, None)
    assert not public.exists() and signed.video.open("rb").read() == stored
    assert not (settings.MEDIA_ROOT / "answers" / "partial").exists()
