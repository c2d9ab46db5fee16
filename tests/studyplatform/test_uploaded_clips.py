"""Test conditions whose clips researchers upload (issue 37): checked, converted, stored
under their SHA-256, mixed with rendered conditions, served privately until the study
takes participants, exported with their source and checksum; bad uploads store nothing.

Every video here is made by ffmpeg (imageio-ffmpeg's) from its test pattern.
"""

import functools
import hashlib
import io
import subprocess
import zipfile
from pathlib import Path

import imageio_ffmpeg
import pytest
from django.core.files.uploadedfile import SimpleUploadedFile
from django.urls import reverse

from studyplatform.actions import GenerateOptions, do_duplicate_study, do_generate_stimuli
from studyplatform.actions.clips import (
    ClipUploadRejected,
    do_import_clips,
    do_remove_uploaded_clip,
    do_upload_clip,
)
from studyplatform.actions.stimuli import IdenticalClips
from studyplatform.files.video_files import _index_first
from studyplatform.lib.uploads import mismatched_pairs
from studyplatform.models import Condition, Stimulus, Study, Trial, UploadedClip
from tests.conftest import as_draft, tiny_webm

pytestmark = pytest.mark.django_db


@functools.lru_cache(maxsize=64)  # the same pattern is asked for by many tests
def make_video(
    codec: str = "libx264",
    size: str = "320x240",
    seconds: float = 2.0,
    container: str = "mp4",
    faststart: bool = True,
) -> bytes:
    """Return a test-pattern video made by ffmpeg."""
    extra = ["-pix_fmt", "yuv420p"] if codec == "libx264" else []
    if container == "mp4" and faststart:
        extra += ["-movflags", "+faststart"]
    command = [
        imageio_ffmpeg.get_ffmpeg_exe(),
        "-v",
        "error",
        "-f",
        "lavfi",
        "-i",
        f"testsrc=size={size}:rate=25",
        "-t",
        str(seconds),
        "-c:v",
        codec,
        *extra,
        "-f",
        container,
        "-",
    ]
    if container in ("mp4", "mov"):  # these need a seekable output: a temporary file
        import tempfile

        with tempfile.NamedTemporaryFile(suffix=f".{container}") as out:
            subprocess.run([*command[:-1], "-y", out.name], check=True, capture_output=True)
            return Path(out.name).read_bytes()
    return subprocess.run(command, check=True, capture_output=True).stdout


def upload(data: bytes, name: str = "clip.mp4") -> SimpleUploadedFile:
    return SimpleUploadedFile(name, data)


@pytest.fixture
def mixed(spine):
    """The demo spine study as a draft whose spine-off condition is uploaded clips."""
    as_draft(spine)
    Condition.objects.filter(study=spine, key="spine-off").update(source="uploaded", parameters={})
    return spine


def _condition(study: Study, key: str) -> Condition:
    return study.conditions.get(key=key)


def _private(settings) -> Path:
    return Path(settings.SIGNSTUDY_PRIVATE_MEDIA_ROOT)


def test_an_h264_mp4_with_its_index_first_is_kept_byte_for_byte(mixed, settings):
    data = make_video()
    item = mixed.items.get(key="S1")
    clip = do_upload_clip(_condition(mixed, "spine-off"), item, upload(data, "S1 filmed.mp4"))
    assert clip.sha256 == clip.source_sha256 == hashlib.sha256(data).hexdigest()
    assert clip.converted == "" and clip.source_codec == "h264"
    assert clip.video.name == f"uploads/{clip.sha256}.mp4"
    assert (_private(settings) / clip.video.name).read_bytes() == data
    assert (_private(settings) / clip.poster.name).read_bytes().startswith(b"\x89PNG")
    assert (clip.width, clip.height, clip.duration_ms, clip.frame_count) == (320, 240, 2000, 50)
    assert clip.frame_rate == 25.0 and clip.original_name == "S1 filmed.mp4"
    # It is the item's ready clip in that condition at once, named by its content.
    stimulus = Stimulus.objects.get(condition__key="spine-off", item=item)
    assert stimulus.status == Stimulus.Status.READY and stimulus.upload == clip
    assert stimulus.content_hash == stimulus.sha256 == clip.sha256
    assert stimulus.video_url == f"/clips/{clip.video.name}"


@pytest.mark.parametrize(
    ("codec", "container", "faststart", "converted"),
    [
        ("mpeg4", "mov", False, "transcoded"),  # QuickTime, MPEG-4 part 2: re-encoded
        ("libx264", "mov", False, "remuxed"),  # H.264 in QuickTime: frames copied
        ("libx264", "mp4", False, "remuxed"),  # index last: moved first
    ],
)
def test_what_a_browser_might_not_play_becomes_an_h264_mp4_with_its_index_first(
    mixed, settings, codec, container, faststart, converted
):
    data = make_video(codec, container=container, faststart=faststart)
    clip = do_upload_clip(
        _condition(mixed, "spine-off"), mixed.items.get(key="S2"), upload(data, f"S2.{container}")
    )
    assert clip.converted == converted and clip.video.name.endswith(".mp4")
    assert clip.source_sha256 == hashlib.sha256(data).hexdigest() != clip.sha256
    stored = _private(settings) / clip.video.name
    assert _index_first(stored)
    frames = imageio_ffmpeg.read_frames(str(stored))
    facts = next(frames)
    frames.close()
    assert facts["codec"] == "h264" and facts["size"] == (320, 240)
    assert clip.frame_count == 50 and clip.duration_ms == 2000


def test_an_odd_sized_video_is_cropped_by_one_pixel_for_h264(mixed):
    data = make_video("mpeg4", size="321x241", container="mov", faststart=False)
    clip = do_upload_clip(
        _condition(mixed, "spine-off"), mixed.items.get(key="S3"), upload(data, "odd.mov")
    )
    assert (clip.width, clip.height, clip.converted) == (320, 240, "transcoded")


def test_a_webm_stays_a_webm(mixed, settings):
    clip = do_upload_clip(
        _condition(mixed, "spine-off"), mixed.items.get(key="S4"), upload(tiny_webm(), "S4.webm")
    )
    assert clip.video.name.endswith(".webm") and clip.source_codec == "vp8"
    assert clip.frame_count == 15 and clip.width == 160


def _nothing_stored(settings) -> None:
    assert not UploadedClip.objects.exists()
    uploads = _private(settings) / "uploads"
    assert not uploads.exists() or not any(uploads.iterdir())


@pytest.mark.parametrize(
    ("data", "message"),
    [
        (b"<html><script>alert(1)</script></html>", "is not a video"),
        (b"\x00\x00\x00\x18ftypmp42" + b"\x00" * 200, "does not decode"),
    ],
)
def test_what_is_not_a_whole_video_is_refused_naming_it(mixed, settings, data, message):
    with pytest.raises(ClipUploadRejected, match=message):
        do_upload_clip(
            _condition(mixed, "spine-off"), mixed.items.get(key="S1"), upload(data, "bad.mp4")
        )
    _nothing_stored(settings)


def test_a_video_cut_short_is_refused(mixed, settings):
    data = make_video(seconds=3.0, faststart=True)
    with pytest.raises(ClipUploadRejected, match="does not decode to its end"):
        do_upload_clip(
            _condition(mixed, "spine-off"),
            mixed.items.get(key="S1"),
            upload(data[: len(data) // 2], "cut.mp4"),
        )
    _nothing_stored(settings)


def test_an_oversized_upload_and_a_rendered_condition_are_refused(mixed, settings, monkeypatch):
    import studyplatform.actions.clips as clips

    monkeypatch.setattr(clips, "MAX_CLIP_BYTES", 1000)
    with pytest.raises(ClipUploadRejected, match="larger than"):
        do_upload_clip(
            _condition(mixed, "spine-off"),
            mixed.items.get(key="S1"),
            upload(make_video(), "big.mp4"),
        )
    with pytest.raises(ClipUploadRejected, match="renders its clips"):
        do_upload_clip(
            _condition(mixed, "spine-on"), mixed.items.get(key="S1"), upload(make_video(), "S1.mp4")
        )
    _nothing_stored(settings)


def test_a_clip_participants_may_have_seen_is_not_replaced(mixed):
    condition, item = _condition(mixed, "spine-off"), mixed.items.get(key="S1")
    clip = do_upload_clip(condition, item, upload(make_video()))
    Study.objects.filter(pk=mixed.pk).update(status="open")
    mixed.refresh_from_db()
    condition.refresh_from_db()
    with pytest.raises(Exception, match="new version"):
        do_upload_clip(condition, item, upload(make_video(seconds=1.0)))
    with pytest.raises(Exception, match="new version"):
        do_remove_uploaded_clip(clip)
    assert UploadedClip.objects.get().sha256 == clip.sha256


def _zip(files: dict[str, bytes], manifest: str | None, method=zipfile.ZIP_STORED) -> io.BytesIO:
    buffer = io.BytesIO()
    with zipfile.ZipFile(buffer, "w", method) as archive:
        if manifest is not None:
            archive.writestr("manifest.csv", manifest)
        for name, data in files.items():
            archive.writestr(name, data)
    buffer.seek(0)
    buffer.name = "clips.zip"
    return buffer


def test_a_zip_with_a_manifest_uploads_every_clip_it_names(mixed):
    files = {f"films/S{n}.mp4": make_video(seconds=1.0 + n / 5) for n in range(1, 6)}
    manifest = "item,condition,file\n" + "".join(
        f"S{n},spine-off,films/S{n}.mp4\n" for n in range(1, 6)
    )
    clips = do_import_clips(mixed, _zip(files, manifest))
    assert len(clips) == 5 and UploadedClip.objects.count() == 5
    assert {c.item.key: c.duration_ms for c in clips} == {
        f"S{n}": 1000 + 200 * n for n in range(1, 6)
    }


@pytest.mark.parametrize(
    ("manifest", "files", "message"),
    [
        (
            "item,condition,file\nS1,spine-off,S1.mp4\nS2,spine-off,gone.mp4\n",
            ["S1.mp4"],
            r"line 3: the zip has no file 'gone.mp4'",
        ),
        ("item,file\nS1,S1.mp4\n", ["S1.mp4"], "no condition column"),
        ("item,condition,file\nS9,spine-off,S1.mp4\n", ["S1.mp4"], "no item 'S9'"),
        ("item,condition,file\nS1,spine-on,S1.mp4\n", ["S1.mp4"], "renders its clips"),
        (
            "item,condition,file\nS1,spine-off,S1.mp4\nS1,spine-off,S1.mp4\n",
            ["S1.mp4"],
            "a second clip of S1",
        ),
        (None, ["S1.mp4"], "no manifest.csv"),
        (
            "item,condition,file\nS1,spine-off,S1.mp4\nS2,spine-off,bad.mp4\n",
            ["S1.mp4", "bad.mp4"],
            "bad.mp4 is not a video",
        ),
    ],
)
def test_a_zip_that_is_wrong_anywhere_stores_nothing(mixed, settings, manifest, files, message):
    good = make_video(seconds=1.0)
    contents = {name: (b"not a video at all" if name == "bad.mp4" else good) for name in files}
    with pytest.raises(ClipUploadRejected, match=message):
        do_import_clips(mixed, _zip(contents, manifest))
    _nothing_stored(settings)


def test_a_zip_bomb_and_a_non_zip_are_refused(mixed, settings):
    bomb = _zip(
        {"S1.mp4": b"\x00" * (64 * 1024**2)},
        "item,condition,file\nS1,spine-off,S1.mp4\n",
        zipfile.ZIP_DEFLATED,
    )
    assert len(bomb.getvalue()) < 1024**2
    with pytest.raises(ClipUploadRejected, match="zip bomb"):
        do_import_clips(mixed, bomb)
    with pytest.raises(ClipUploadRejected, match="not a zip"):
        do_import_clips(mixed, io.BytesIO(make_video()))
    _nothing_stored(settings)


def test_generation_renders_the_rendered_conditions_and_counts_missing_uploads(mixed):
    off = _condition(mixed, "spine-off")
    do_upload_clip(off, mixed.items.get(key="S1"), upload(make_video()))
    result = do_generate_stimuli(mixed, GenerateOptions(enqueue=False))
    assert (result.total, result.queued, result.ready, result.missing) == (10, 5, 1, 4)
    missing = Stimulus.objects.filter(condition=off, status=Stimulus.Status.MISSING)
    assert sorted(missing.values_list("item__key", flat=True)) == ["S2", "S3", "S4", "S5"]
    # An upload after generation is ready at once; generation again keeps it so.
    do_upload_clip(off, mixed.items.get(key="S2"), upload(make_video(seconds=1.0)))
    assert do_generate_stimuli(mixed, GenerateOptions(enqueue=False)).missing == 3


def test_two_conditions_showing_the_same_file_are_identical_clips(mixed):
    on = _condition(mixed, "spine-on")
    Condition.objects.filter(pk=on.pk).update(source="uploaded", parameters={})
    on.refresh_from_db()
    data = make_video()
    for key in ("spine-on", "spine-off"):
        do_upload_clip(_condition(mixed, key), mixed.items.get(key="S1"), upload(data))
    with pytest.raises(IdenticalClips, match="S1"):
        do_generate_stimuli(mixed, GenerateOptions(enqueue=False))


def test_pairs_compared_are_warned_of_when_length_or_size_differ(mixed):
    on, off = _condition(mixed, "spine-on"), _condition(mixed, "spine-off")
    item = mixed.items.get(key="S1")
    block = mixed.blocks.order_by("position").last()
    Trial.objects.create(
        study=mixed,
        block=block,
        key="pair-s1",
        kind="pairwise",
        item=item,
        condition_a=on,
        condition_b=off,
    )
    do_upload_clip(off, item, upload(make_video(size="640x360", seconds=3.0)))
    Stimulus.objects.create(
        condition=on,
        item=item,
        status="ready",
        content_hash="x" * 64,
        width=640,
        height=480,
        duration_ms=2000,
    )
    warnings = mismatched_pairs(mixed)
    assert warnings == [
        "S1: spine-on and spine-off differ in frame size (640×480 and 640×360).",
        "S1: spine-on and spine-off differ in length by 50 % (2.00 s and 3.00 s).",
    ]


def test_an_uploaded_clip_is_private_until_the_study_takes_participants(mixed, client, bob, alice):
    clip = do_upload_clip(
        _condition(mixed, "spine-off"), mixed.items.get(key="S1"), upload(make_video())
    )
    url = f"/clips/{clip.video.name}"
    assert client.get(url).status_code == 404  # a draft: nobody outside its researchers
    client.force_login(alice)
    assert client.get(url).status_code == 404  # another researcher's study
    client.force_login(bob)
    assert client.get(url).status_code == 200
    assert client.get(f"/clips/{clip.poster.name}")["Content-Type"] == "image/png"
    client.logout()
    Study.objects.filter(pk=mixed.pk).update(status="pilot")
    response = client.get(url, HTTP_RANGE="bytes=0-99")
    assert response.status_code == 206 and response["Content-Type"] == "video/mp4"
    assert response["Content-Range"].startswith("bytes 0-99/")
    assert response["X-Content-Type-Options"] == "nosniff"
    Study.objects.filter(pk=mixed.pk).update(status="closed")
    assert client.get(url).status_code == 404
    assert client.get("/clips/uploads/../../etc/passwd").status_code == 404


def test_a_copy_of_the_study_keeps_its_uploaded_clips(mixed, bob):
    clip = do_upload_clip(
        _condition(mixed, "spine-off"), mixed.items.get(key="S1"), upload(make_video())
    )
    copy = do_duplicate_study(mixed, owner=bob)
    copied = UploadedClip.objects.get(condition__study=copy)
    assert copied.condition.source == "uploaded" and copied.item.key == "S1"
    assert (copied.video.name, copied.sha256) == (clip.video.name, clip.sha256)
    do_generate_stimuli(copy, GenerateOptions(enqueue=False))
    assert Stimulus.objects.get(condition=copied.condition, item=copied.item).status == "ready"


def test_an_uploaded_condition_takes_no_technique_settings(mixed):
    from django.core.exceptions import ValidationError

    condition = _condition(mixed, "spine-off")
    condition.parameters = {"spine": False}
    with pytest.raises(ValidationError, match="renders nothing"):
        condition.full_clean()


# --- conversions in the background (issue 51) ------------------------------------------


def test_an_upload_is_taken_at_once_and_converted_by_its_job(mixed, settings):
    """The request keeps the file and queues a job; the clip exists once the job ran."""
    from studyplatform.actions.clip_uploads import do_queue_clip, incoming_directory
    from studyplatform.models import ClipUpload
    from studyplatform.tasks import prepare_clips_now

    off, item = _condition(mixed, "spine-off"), mixed.items.get(key="S1")
    job = do_queue_clip(off, item, upload(make_video(), "S1 filmed.mp4"))
    assert job.status == ClipUpload.Status.QUEUED and not UploadedClip.objects.exists()
    assert (incoming_directory() / job.incoming).is_file()
    assert prepare_clips_now(job.pk) == ClipUpload.Status.DONE
    job.refresh_from_db()
    assert job.done == 1 and "Clip of S1 in spine-off saved" in job.message
    assert UploadedClip.objects.get().original_name == "S1 filmed.mp4"
    assert not (incoming_directory() / job.incoming).exists()
    assert prepare_clips_now(job.pk) == ClipUpload.Status.DONE  # a second delivery: nothing


def test_what_the_request_can_tell_is_refused_at_once_and_the_rest_by_the_job(mixed, settings):
    from studyplatform.actions.clip_uploads import do_queue_clip, incoming_directory
    from studyplatform.models import ClipUpload
    from studyplatform.tasks import prepare_clips_now

    off, item = _condition(mixed, "spine-off"), mixed.items.get(key="S1")
    with pytest.raises(ClipUploadRejected, match="is not a video"):
        do_queue_clip(off, item, upload(b"<html></html>", "page.mp4"))
    assert not ClipUpload.objects.exists()
    cut = make_video(seconds=2.0)[:-4000]  # a video by its content, cut short
    job = do_queue_clip(off, item, upload(cut, "cut.mp4"))
    assert prepare_clips_now(job.pk) == ClipUpload.Status.FAILED
    job.refresh_from_db()
    assert "does not decode to its end" in job.message
    _nothing_stored(settings)
    assert not any(incoming_directory().iterdir())


def test_a_zip_job_reports_each_clip_and_stores_all_or_nothing(mixed, settings):
    from studyplatform.actions.clip_uploads import do_queue_clips_zip
    from studyplatform.models import ClipUpload
    from studyplatform.tasks import prepare_clips_now

    files = {f"S{n}.mp4": make_video(seconds=1.0) for n in range(1, 4)}
    manifest = "item,condition,file\n" + "".join(f"S{n},spine-off,S{n}.mp4\n" for n in range(1, 4))
    job = do_queue_clips_zip(mixed, _zip(files, manifest))
    assert job.total == 3 and job.status == ClipUpload.Status.QUEUED
    with pytest.raises(ClipUploadRejected, match="no item 'S9'"):
        do_queue_clips_zip(mixed, _zip(files, manifest.replace("S3,", "S9,")))
    assert prepare_clips_now(job.pk) == ClipUpload.Status.DONE
    job.refresh_from_db()
    assert job.done == 3 and UploadedClip.objects.count() == 3
    files["S2.mp4"] = files["S2.mp4"][:-4000]
    broken = do_queue_clips_zip(mixed, _zip(files, manifest))
    before = sorted(UploadedClip.objects.values_list("pk", "sha256"))
    assert prepare_clips_now(broken.pk) == ClipUpload.Status.FAILED
    assert sorted(UploadedClip.objects.values_list("pk", "sha256")) == before


@pytest.mark.django_db(transaction=True)
def test_the_page_answers_a_script_with_the_jobs_outcome(mixed, client, bob):
    """Where jobs run in the process (no broker: the job runs as the upload commits),
    the answer carries the job's outcome; with a broker it says the upload is converting
    (the page then lists it, as it lists a refused one)."""
    client.force_login(bob)
    url = reverse("admin:studyplatform_study_uploads", args=[mixed.pk])
    fields = {"condition": _condition(mixed, "spine-off").pk, "item": mixed.items.get(key="S1").pk}
    headers = {"Accept": "application/json"}
    cut = upload(make_video(seconds=2.0)[:-4000], "cut.mp4")
    refused = client.post(url, {**fields, "clip": cut}, headers=headers)
    assert refused.status_code == 400 and "does not decode" in refused.json()["error"]
    clip = upload(make_video(), "ok.mp4")
    saved = client.post(url, {**fields, "clip": clip}, headers=headers)
    assert saved.status_code == 200 and "saved" in saved.json()["saved"]
    page = client.get(url).content.decode()
    assert "cut.mp4" in page and "Nothing saved" in page  # the refused one, listed


def test_an_upload_whose_job_was_lost_is_failed_and_its_file_deleted(mixed, settings):
    from datetime import timedelta

    from django.utils import timezone

    from studyplatform.actions.clip_uploads import (
        do_fail_stale_clip_uploads,
        do_queue_clip,
        incoming_directory,
    )
    from studyplatform.models import ClipUpload

    off, item = _condition(mixed, "spine-off"), mixed.items.get(key="S1")
    job = do_queue_clip(off, item, upload(make_video(), "S1.mp4"))
    assert do_fail_stale_clip_uploads(24) == 0
    ClipUpload.objects.filter(pk=job.pk).update(created_at=timezone.now() - timedelta(days=2))
    assert do_fail_stale_clip_uploads(24) == 1
    job.refresh_from_db()
    assert job.status == "failed" and "upload it again" in job.message
    assert not (incoming_directory() / job.incoming).exists()


def test_the_generate_page_counts_uploaded_clips_as_ready(mixed, client):
    """Issue 55, item 7: the Generate page said "0 are rendered already" with uploaded
    clips ready (it looked only in the rendered clips' folder)."""
    off = _condition(mixed, "spine-off")
    for key in ("S1", "S2"):
        do_upload_clip(off, mixed.items.get(key=key), upload(make_video(seconds=1.0)))
    client.force_login(mixed.owner)
    html = client.get(reverse("admin:studyplatform_study_generate", args=[mixed.pk])).content
    assert b'<span id="generate-on-disk">2 are ready</span>' in html
