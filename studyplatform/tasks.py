"""Celery jobs: render one stimulus clip, prepare a recording, clean abandoned uploads.

A job is acknowledged only after it finished (``CELERY_TASK_ACKS_LATE``), and the clip
file is moved into place whole; a worker killed mid-render leaves the stimulus
"rendering", never "ready", and the broker hands the job to another worker.
"""

import warnings
from pathlib import Path

from celery import shared_task
from django.conf import settings

from stimuli.clips import ClipSpec, render
from studyplatform.jobs.queue import (
    APPLY_RETENTION,
    CLEAN_ABANDONED_UPLOADS,
    PREPARE_AVATAR,
    PREPARE_CLIPS,
    PREPARE_RECORDING,
    RENDER_STIMULUS,
)
from studyplatform.lib.stimuli import SUBDIRECTORY, clips_folder
from studyplatform.models import Stimulus


def render_now(stimulus_id: int) -> str:
    """Render one stimulus in this process; return its final status."""
    from studyplatform.actions.stimuli import (
        do_fail_stimulus,
        do_record_rendered_stimulus,
        do_start_rendering,
    )

    stimulus = Stimulus.objects.filter(pk=stimulus_id).first()
    if stimulus is None:
        return "missing"
    if stimulus.status == Stimulus.Status.READY and stimulus.video:
        return stimulus.status
    if stimulus.condition.is_uploaded:
        return stimulus.status  # the researcher's file, never rendered
    do_start_rendering(stimulus)
    try:
        spec = ClipSpec.from_dict(stimulus.parameters)
        clip = render(spec, clips_folder())
    except Exception as error:  # any failure is recorded on the clip, for the admin
        return do_fail_stimulus(stimulus, error)
    return do_record_rendered_stimulus(stimulus, spec, clip, SUBDIRECTORY)


@shared_task(name=RENDER_STIMULUS, acks_late=True, reject_on_worker_lost=True)
def render_stimulus(stimulus_id: int) -> str:
    """Render one stimulus (Celery job)."""
    return render_now(stimulus_id)


def prepare_now(recording_id: int) -> str:
    """Capture (a video), fit and check one recording in this process; return its status.

    A video's landmarks are found with MediaPipe; every recording is fitted to the rig
    and its holds are extracted, so one that cannot be retimed fails here, with the
    reason, instead of when its clips render.
    """
    from studyplatform.actions.recordings import (
        do_fail_recording,
        do_finish_recording,
        do_report_capture_progress,
    )
    from studyplatform.models import Recording

    recording = Recording.objects.filter(pk=recording_id).select_related("item").first()
    if recording is None:
        return "missing"
    if recording.status == Recording.Status.READY:
        return recording.status
    try:
        quality, pose, sheet, bvh = _prepare(recording, do_report_capture_progress)
    except (ValueError, OSError) as error:  # the engine's errors name the problem
        return do_fail_recording(recording, error)
    return do_finish_recording(recording, quality, pose, sheet, bvh)


def _prepare(recording, report_progress) -> tuple[dict, bytes | None, bytes | None, bytes | None]:
    from studyplatform.lib.recordings import retimes_recordings
    from synthesis.capture import captured_hand, parse_pose, read_pose
    from synthesis.skeleton.bvh import BvhWarning, read_bvh
    from synthesis.timing.recordings import Recording as Performance

    item, path = recording.item, Path(recording.upload.path)
    side = (item.parameters or {}).get("side", "right")
    pose = bvh = None
    sheet = None
    if recording.is_video:
        pose, sheet = _captured(recording, path, side, report_progress)
        landmarks = parse_pose(pose, path.name)
    elif path.suffix.lower() == ".pose":
        landmarks = read_pose(path)
    elif path.suffix.lower() in (".fbx", ".glb"):  # converted to BVH: what clips read
        from studyplatform.confine import ConfinedError, run_task
        from synthesis.skeleton.bvh import parse_bvh

        landmarks = None
        try:  # assimp and the glTF reader run confined, as on upload
            read = run_task("motion", path.read_bytes(), recording.upload.name, path.suffix.lower())
        except ConfinedError as error:
            raise ValueError(str(error)) from None
        bvh = read["bvh"].encode()
        motion = parse_bvh(read["bvh"], path.name)
        quality = {"frames": motion.n_frames, "fps": motion.rate_hz}
        quality["warnings"] = _mapping_warnings(motion, side, path.name)
    else:
        landmarks = None
        with warnings.catch_warnings(record=True) as said:
            warnings.simplefilter("always", BvhWarning)
            motion = read_bvh(path)
        quality = {"frames": motion.n_frames, "fps": motion.rate_hz}
        quality["warnings"] = [str(w.message) for w in said if issubclass(w.category, BvhWarning)]
        quality["warnings"] += _mapping_warnings(motion, side, path.name)
    if landmarks is not None:
        hand = captured_hand(landmarks, side)
        motion, quality = hand.motion, hand.quality(landmarks)
    # Conditions that retime the recording need its holds: a recording in which they
    # cannot be found (another word, say) fails now rather than when its clips render.
    performance = Performance.from_motion(motion, item.text, side)
    if retimes_recordings(item.study):
        quality["holds_found"] = len(performance.extraction.timing.letters)
    return quality, pose, sheet, bvh


def _mapping_warnings(motion, side: str, name: str) -> list[str]:
    """Return what the recording's joint mapping leaves at rest on the signing side (a
    render would show that arm or hand still, as ``render-bvh`` warns; issue 54)."""
    from synthesis.skeleton.mapping import detect_mapping

    signing = {"fingers", f"{side} arm", f"{side} hand's fingers"}
    warning = detect_mapping(motion.skeleton).at_rest_warning(name, signing)
    return [warning] if warning else []


def _captured(recording, path: Path, side: str, report_progress) -> tuple[bytes, bytes | None]:
    """Return a video recording's landmarks (.pose) and contact sheet (PNG or None),
    captured confined: MediaPipe and the video's decoder read the researcher's file in
    a child process with limits, no network and nothing else readable (issue 51)."""
    import base64
    import json

    from studyplatform.confine import CAPTURE, ConfinedError, run_task

    options = {
        "suffix": path.suffix.lower(),
        "mirrored": recording.mirrored,
        "side": side,
        "one_hand": side if recording.one_hand else None,
    }
    try:
        read = run_task(
            "capture",
            path.read_bytes(),
            recording.upload.name,  # as the researcher sees it in media
            json.dumps(options),
            CAPTURE,
            progress=lambda percent: report_progress(recording, percent),
        )
    except ConfinedError as error:
        raise ValueError(str(error)) from None
    sheet = base64.b64decode(read["sheet"]) if read["sheet"] else None
    return base64.b64decode(read["pose"]), sheet


@shared_task(name=PREPARE_RECORDING, acks_late=True, reject_on_worker_lost=True)
def prepare_recording(recording_id: int) -> str:
    """Capture, fit and check one recording (Celery job)."""
    return prepare_now(recording_id)


def prepare_clips_now(upload_id: int) -> str:
    """Convert and store one clip upload (a video or a zip) in this process."""
    from studyplatform.actions.clip_uploads import do_prepare_clip_upload
    from studyplatform.models import ClipUpload

    job = ClipUpload.objects.filter(pk=upload_id).select_related("study").first()
    if job is None:
        return "missing"
    if job.status in (ClipUpload.Status.DONE, ClipUpload.Status.FAILED):
        return job.status
    return do_prepare_clip_upload(job)


@shared_task(name=PREPARE_CLIPS, acks_late=True, reject_on_worker_lost=True)
def prepare_clips(upload_id: int) -> str:
    """Make an uploaded clip, or a zip of them, playable and store it (Celery job)."""
    return prepare_clips_now(upload_id)


@shared_task(name=CLEAN_ABANDONED_UPLOADS)
def clean_abandoned_uploads() -> int:
    """Delete unfinished signed-answer uploads, and clip uploads whose conversion was
    lost, older than the configured age (beat job)."""
    from studyplatform.actions.clip_uploads import do_fail_stale_clip_uploads
    from studyplatform.actions.uploads import do_remove_abandoned_uploads

    hours = settings.SIGNSTUDY_PARTIAL_UPLOAD_MAX_AGE_HOURS
    return len(do_remove_abandoned_uploads(hours)) + do_fail_stale_clip_uploads(hours)


@shared_task(name=APPLY_RETENTION)
def apply_retention() -> int:
    """Delete personal data whose study's retention period has passed (beat job)."""
    from studyplatform.actions import do_apply_retention

    result = do_apply_retention()
    return result.personal_answers + result.videos + result.recruitment_ids


def prepare_avatar_now(avatar_id: int) -> str:
    """Render an uploaded avatar's preview stills in this process; return its status."""
    from studyplatform.actions.avatars import do_fail_avatar_previews, do_finish_avatar_previews
    from studyplatform.models import Avatar
    from synthesis.interchange.previews import avatar_stills

    avatar = Avatar.objects.filter(pk=avatar_id).first()
    if avatar is None:
        return "missing"
    try:
        stills = avatar_stills(avatar.file.path)
    except Exception as error:  # any failure is recorded on the avatar, for the admin
        return do_fail_avatar_previews(avatar, error)
    do_finish_avatar_previews(avatar, stills)
    return Avatar.Status.READY


@shared_task(name=PREPARE_AVATAR, acks_late=True, reject_on_worker_lost=True)
def prepare_avatar(avatar_id: int) -> str:
    """Render an avatar's preview stills (Celery job)."""
    return prepare_avatar_now(avatar_id)
