"""Test generating a study's stimuli: caching by content hash, re-rendering, failures."""

import json
import os
import time

import pytest
from django.core.management import CommandError, call_command

from stimuli.clips import ClipError, file_sha256
from studyplatform.actions.stimuli import GenerateOptions, do_generate_stimuli, do_retry_stimuli
from studyplatform.lib.stimuli import clip_spec
from studyplatform.models import Condition, Stimulus, Trial
from synthesis.render.video import count_frames

pytestmark = pytest.mark.django_db
SMALL = {"width": 64, "height": 48, "rate_hz": 20.0}


@pytest.fixture
def small_study(fingerspelling, settings, tmp_path, renderable):
    """The demo fingerspelling study cut to one comparison page, rendered tiny."""
    settings.MEDIA_ROOT = tmp_path
    Trial.objects.filter(block__study=fingerspelling).exclude(key="cmp-01").delete()
    for condition in fingerspelling.conditions.all():
        condition.parameters = {**condition.parameters, **SMALL}
        condition.save()
    return fingerspelling


def _generate(study, capture, **options):
    with capture(execute=True):
        return do_generate_stimuli(study, GenerateOptions(**options))


def test_generating_renders_each_clip_once(small_study, django_capture_on_commit_callbacks):
    first = _generate(small_study, django_capture_on_commit_callbacks)
    assert (first.total, first.queued, first.ready) == (2, 2, 0)
    clips = list(Stimulus.objects.filter(pk__in=first.stimulus_ids))
    for stimulus in clips:
        assert stimulus.status == Stimulus.Status.READY, stimulus.error
        assert stimulus.video.name == f"stimuli/{stimulus.content_hash}.mp4"
        assert count_frames(stimulus.video.path) == stimulus.frame_count > 20
        assert stimulus.size_bytes == stimulus.video.size and len(stimulus.sha256) == 64
        assert stimulus.parameters["width"] == 64 and stimulus.engine_version
    # A second run renders nothing.
    again = _generate(small_study, django_capture_on_commit_callbacks)
    assert (again.queued, again.ready) == (0, 2)


def test_changing_one_parameter_re_renders_exactly_the_affected_clips(
    small_study, django_capture_on_commit_callbacks
):
    first = _generate(small_study, django_capture_on_commit_callbacks)
    before = {s.pk: (s.content_hash, s.rendered_at) for s in Stimulus.objects.all()}
    trial = Trial.objects.get(key="cmp-01")
    changed = trial.condition_a
    changed.parameters = {**changed.parameters, "seed": 7}
    changed.save()
    second = _generate(small_study, django_capture_on_commit_callbacks)
    assert second.queued == 1 and set(second.stimulus_ids) == set(first.stimulus_ids)
    for stimulus in Stimulus.objects.all():
        same = before[stimulus.pk] == (stimulus.content_hash, stimulus.rendered_at)
        assert same == (stimulus.condition_id != changed.pk)
        assert stimulus.status == Stimulus.Status.READY


def test_a_failed_clip_is_recorded_and_retried_alone(
    small_study, django_capture_on_commit_callbacks, monkeypatch
):
    import stimuli.clips

    trial = Trial.objects.get(key="cmp-01")
    real = stimuli.clips.render

    def flaky(spec, directory, progress=None):
        if spec.parameters.get("timing") == trial.condition_b.parameters["timing"]:
            raise RuntimeError("the renderer ran out of memory")
        return real(spec, directory, progress)

    monkeypatch.setattr("studyplatform.tasks.render", flaky)
    _generate(small_study, django_capture_on_commit_callbacks)
    failed = Stimulus.objects.get(condition=trial.condition_b)
    assert failed.status == Stimulus.Status.FAILED
    assert "RuntimeError: the renderer ran out of memory" in failed.error
    assert Stimulus.objects.get(condition=trial.condition_a).status == Stimulus.Status.READY
    monkeypatch.setattr("studyplatform.tasks.render", real)
    with django_capture_on_commit_callbacks(execute=True):
        assert do_retry_stimuli(Stimulus.objects.all()) == 1
    failed.refresh_from_db()
    assert failed.status == Stimulus.Status.READY


def test_bad_condition_parameters_are_named(fingerspelling):
    condition = Condition.objects.get(study=fingerspelling, key="constant")
    condition.parameters = {"timing": "fast"}
    condition.save()
    with pytest.raises(ClipError, match=r"constant × .*Unknown timing 'fast'"):
        do_generate_stimuli(fingerspelling)
    assert not Stimulus.objects.exists()  # nothing half-recorded


def test_conditions_of_an_item_share_its_seed(fingerspelling):
    trial = Trial.objects.filter(block__study=fingerspelling, kind="pairwise").first()
    a = clip_spec(trial.condition_a, trial.item)
    b = clip_spec(trial.condition_b, trial.item)
    assert a.seed == b.seed and a.content_hash() != b.content_hash()


def test_the_command_renders_and_reports(small_study, capsys, django_capture_on_commit_callbacks):
    with django_capture_on_commit_callbacks(execute=True):
        call_command("generate_stimuli", small_study.slug)
    assert "2 clips, 2 rendered, 0 already there, 0 failed" in capsys.readouterr().out
    assert Stimulus.objects.filter(status=Stimulus.Status.READY).count() == 2
    call_command("generate_stimuli", small_study.slug)
    assert "2 clips, 0 rendered, 2 already there" in capsys.readouterr().out
    with pytest.raises(CommandError, match="No study with the slug 'nope'"):
        call_command("generate_stimuli", "nope")


def test_the_command_takes_several_studies_and_checks_them_all_first(small_study, capsys):
    with pytest.raises(CommandError, match="No study with the slug 'nope'"):
        call_command("generate_stimuli", small_study.slug, "nope")
    assert not Stimulus.objects.exists()  # nothing recorded before every slug was found
    with pytest.raises(CommandError, match="--manifest writes one study's manifest"):
        call_command("generate_stimuli", small_study.slug, small_study.slug, "--manifest", "m.json")


def _wait_for_clips(client, url, timeout_s: float = 180.0) -> dict:
    deadline = time.monotonic() + timeout_s
    while time.monotonic() < deadline:
        progress = client.get(url).json()
        if not progress["pending"]:
            return progress
        time.sleep(0.5)
    raise AssertionError(f"clips still pending after {timeout_s} s: {progress}")


@pytest.mark.django_db(transaction=True)
def test_the_admin_action_renders_in_a_background_process_and_shows_progress(
    small_study, client, alice, bob
):
    """Without a broker the action answers at once; a process of its own renders."""
    from django.urls import reverse

    client.force_login(alice)
    changelist = reverse("admin:studyplatform_study_changelist")
    response = client.post(
        changelist, {"action": "generate_stimuli", "_selected_action": [small_study.pk]}
    )
    page = reverse("admin:studyplatform_study_stimuli", args=[small_study.pk])
    assert response.status_code == 302 and response["Location"] == page
    progress_url = reverse("admin:studyplatform_study_stimuli_progress", args=[small_study.pk])
    # The request did not render: a fresh process needs seconds to import the engine.
    assert client.get(progress_url).json()["pending"] == 2
    assert b"stimuli-bar" in client.get(page).content
    progress = _wait_for_clips(client, progress_url)
    assert (progress["total"], progress["done"], progress["failed"], progress["percent"]) == (
        2,
        2,
        0,
        100,
    )
    for stimulus in Stimulus.objects.all():
        assert count_frames(stimulus.video.path) == stimulus.frame_count
    client.force_login(bob)  # another researcher's study is not there for bob
    assert client.get(progress_url).status_code == 404


def test_the_manifest_lists_every_clip_and_renders_the_study_again(
    small_study, client, alice, settings, tmp_path, capsys, django_capture_on_commit_callbacks
):
    from django.urls import reverse

    _generate(small_study, django_capture_on_commit_callbacks)
    call_command("generate_stimuli", small_study.slug, "--manifest", tmp_path / "m.json")
    client.force_login(alice)
    download = client.get(
        reverse("admin:studyplatform_study_stimuli_manifest", args=[small_study.pk])
    )
    assert download["Content-Disposition"] == (
        'attachment; filename="fingerspelling-timing-stimuli.json"'
    )
    manifest = download.json()
    assert manifest == json.loads((tmp_path / "m.json").read_text())
    stimuli = {s.content_hash: s for s in Stimulus.objects.all()}
    assert {clip["hash"] for clip in manifest["clips"]} == set(stimuli)
    for clip in manifest["clips"]:
        stimulus = stimuli[clip["hash"]]
        assert clip["clip"]["sha256"] == stimulus.sha256
        assert clip["clip"]["frame_count"] == stimulus.frame_count
        assert clip["clip"]["size_bytes"] == stimulus.size_bytes
        assert clip["clip"]["video"] == f"{stimulus.content_hash}.mp4"

    # From the manifest alone, into an empty media folder: the same bytes.
    settings.MEDIA_ROOT = tmp_path / "elsewhere"
    call_command("generate_stimuli", "--from-manifest", str(tmp_path / "m.json"))
    assert "2 clips, 2 rendered" in capsys.readouterr().out
    for content_hash, stimulus in stimuli.items():
        again = tmp_path / "elsewhere" / "stimuli" / f"{content_hash}.mp4"
        assert file_sha256(again) == stimulus.sha256
    call_command("generate_stimuli", "--from-manifest", str(tmp_path / "m.json"))
    assert "2 clips, 0 rendered" in capsys.readouterr().out
    (tmp_path / "bad.json").write_text("{}")
    with pytest.raises(CommandError, match="not a stimuli manifest"):
        call_command("generate_stimuli", "--from-manifest", str(tmp_path / "bad.json"))


def test_conditions_of_an_item_open_and_close_on_the_same_frame(fingerspelling, tmp_path):
    """Clip hygiene (issue 6): no condition can be told by its first or last frame."""
    import imageio_ffmpeg
    import numpy as np

    from stimuli.clips import render

    def decoded(path):
        reader = imageio_ffmpeg.read_frames(str(path))
        meta = next(reader)
        width, height = meta["size"]
        return [np.frombuffer(f, np.uint8).reshape(height, width, 3) for f in reader]

    item = fingerspelling.items.get(key="DAVID")
    clips = []
    for condition in fingerspelling.conditions.all():
        spec = clip_spec(condition, item)
        spec = type(spec).from_dict({**spec.to_dict(), **SMALL})
        clips.append(render(spec, tmp_path))
    assert len({(c.width, c.height) for c in clips}) == 1
    frames = [decoded(tmp_path / c.video.name) for c in clips]
    durations = {c.duration_ms for c in clips}
    assert len(durations) > 1  # the conditions differ in timing …
    for ends in (0, -1):  # … but open and close on the same still rest pose
        reference = frames[0][ends].astype(int)
        for other in frames[1:]:
            # The rendered frames are the same (the close-up films every clip's ends from
            # the rest pose's framing, tests/synthesis/test_follow.py); decoded, they
            # differ by the encoder's rate control, which plans a frame's quantiser from
            # the frames around it (measured: up to 1.7 levels at 64×48).
            assert np.abs(other[ends].astype(int) - reference).mean() < 2.5


def test_a_fresh_database_and_a_new_version_reuse_the_rendered_files(
    small_study, django_capture_on_commit_callbacks, alice
):
    """Issue 35: the cache was keyed by rows; a version or a fresh database rendered again."""
    from studyplatform.actions.versions import do_create_study_version

    first = _generate(small_study, django_capture_on_commit_callbacks)
    files = {s.video.path: (s.video.size, s.sha256) for s in Stimulus.objects.all()}
    stamps = {path: os.stat(path).st_mtime_ns for path in files}
    # A new version of the study: the same clips, recorded ready from the files.
    version = do_create_study_version(small_study, owner=alice)
    made = _generate(version, django_capture_on_commit_callbacks)
    assert (made.total, made.queued, made.ready) == (2, 0, 2)
    # A fresh database with the media folder filled: no rows, the same files.
    Stimulus.objects.all().delete()
    again = _generate(small_study, django_capture_on_commit_callbacks)
    assert (again.queued, again.ready) == (0, first.total)
    for stimulus in Stimulus.objects.filter(pk__in=again.stimulus_ids):
        assert stimulus.status == Stimulus.Status.READY
        assert (stimulus.video.size, stimulus.sha256) == files[stimulus.video.path]
    # Clips rendered before facts were kept are measured once, never rendered again.
    for path in files:
        os.remove(path.replace(".mp4", ".json"))
    Stimulus.objects.all().delete()
    measured = _generate(small_study, django_capture_on_commit_callbacks)
    assert measured.queued == 0
    for stimulus in Stimulus.objects.filter(pk__in=measured.stimulus_ids):
        assert stimulus.frame_count == count_frames(stimulus.video.path)
        assert os.path.exists(stimulus.video.path.replace(".mp4", ".json"))
    assert {path: os.stat(path).st_mtime_ns for path in files} == stamps  # never overwritten
