"""Read what a study's stimuli are: the clips its trials need, their specs and progress."""

import zlib
from pathlib import Path

from django.utils.translation import gettext

from stimuli.clips import ClipError, ClipSpec, RenderedClip
from stimuli.manifest import Entry
from studyplatform.lib.recordings import with_item_recording
from studyplatform.models import Block, Condition, Item, Stimulus, Study, Trial, UploadedClip
from studyplatform.rules import item_values, resolve_files
from synthesis.techniques import ClipRequest

# Rendered clips live in MEDIA_ROOT/stimuli, named by their content hash: one file per
# clip, whichever studies, versions or databases use it.
SUBDIRECTORY = "stimuli"


def clips_folder() -> Path:
    """Return the folder of rendered clips."""
    from django.conf import settings

    return Path(settings.MEDIA_ROOT) / SUBDIRECTORY


def clip_spec(condition: Condition, item: Item) -> ClipSpec:
    """Return the clip specification of *condition* applied to *item*.

    The condition's parameters override the item's, and the item's the study's (its
    manual alphabet, :func:`studyplatform.rules.study_values`). The seed is the item's (its
    parameters' ``seed``, else a checksum of its key), so all conditions of an item share
    one performance and one noise. A word's recording, where it has one, is the
    performance of the conditions that retime a capture (:mod:`studyplatform.lib.recordings`);
    a condition's own avatar is its file (the avatar technique's ``avatar_file``). A
    file setting's reference (``recording:12``) becomes its stored file
    (:mod:`studyplatform.rules.files`); ClipError names one the study may not use.
    """
    study = condition.study
    parameters = {**item_values(study, item), **(condition.parameters or {})}
    # References to stored files become their paths here, and only here (issue 51).
    parameters = resolve_files(parameters, study.owner)
    parameters.setdefault("seed", zlib.crc32(item.key.encode()))
    parameters = with_item_recording(parameters, item, condition.key)
    if condition.avatar_id is not None:
        # The file's content, not its path, names the clip (ClipSpec hashes files).
        parameters["avatar_file"] = condition.avatar.file.path
    return ClipSpec.from_request(ClipRequest.from_parameters(item.kind, item.text, parameters))


def needed_pairs(study: Study) -> list[tuple[Condition, Item]]:
    """Return the (condition, item) pairs the study's trials show, in design order.

    Under Latin-square rotation a trial block's item is shown in every condition.
    """
    pairs = []
    trials = Trial.objects.filter(block__study=study).select_related(
        "block", "item", "condition_a", "condition_b"
    )
    every_condition = list(study.conditions.all())
    for trial in trials:
        shown = [trial.condition_a, trial.condition_b]
        rotated = study.rotate_conditions and trial.block.kind == Block.Kind.TRIALS
        if rotated and trial.condition_a is not None:
            shown = every_condition  # participants' rows relabel the conditions
        for condition in shown:
            if trial.item is not None and condition is not None:
                pair = (condition, trial.item)
                if pair not in pairs:
                    pairs.append(pair)
    return sorted(pairs, key=lambda p: (p[1].position, p[0].position))


def clips_on_disk(hashed: list[tuple[Condition, Item, str]]) -> int:
    """Return how many of the :func:`hashed_pairs` clips are ready without rendering: an
    uploaded condition's clip that was uploaded (hashed_pairs leaves out the others), and
    a rendered one whose files are in the clips folder, whichever study, version or
    database rendered them."""
    from stimuli.clips import clip_files

    folder = clips_folder()
    return sum(
        condition.is_uploaded
        or all(path.is_file() for path in clip_files(folder, content_hash)[:2])
        for condition, _, content_hash in hashed
    )


def files_exist(stimulus: Stimulus) -> bool:
    """Return whether the stimulus's video file is in storage."""
    return bool(stimulus.video) and stimulus.video.storage.exists(stimulus.video.name)


def stimuli_progress(study: Study) -> dict:
    """Return the study's clips by status, with each failure's error (for the admin)."""
    stimuli = Stimulus.objects.filter(condition__study=study).select_related("condition", "item")
    counts = {status: 0 for status in Stimulus.Status.values}
    failures = []
    for stimulus in stimuli:
        counts[stimulus.status] += 1
        if stimulus.status == Stimulus.Status.FAILED:
            failures.append({"id": stimulus.pk, "clip": str(stimulus), "error": stimulus.error})
    total = sum(counts.values())
    done = counts[Stimulus.Status.READY]
    return {
        "total": total,
        "done": done,
        "failed": counts[Stimulus.Status.FAILED],
        "missing": counts[Stimulus.Status.MISSING],
        "pending": counts[Stimulus.Status.PENDING] + counts[Stimulus.Status.RENDERING],
        "percent": round(100 * done / total) if total else 0,
        "failures": failures,
    }


def study_manifest(study: Study) -> list[Entry]:
    """Return the manifest entries of the study's clips: every rendered clip's spec and facts.

    Clips not rendered yet appear with their spec only, so the manifest still renders them.
    Uploaded clips have no spec: :func:`uploaded_manifest` lists them.
    """
    entries = []
    stimuli = Stimulus.objects.filter(condition__study=study, condition__source="rendered")
    stimuli = stimuli.select_related("condition", "item")
    for stimulus in stimuli.order_by("item__position", "condition__position", "pk"):
        clip = None
        if stimulus.status == Stimulus.Status.READY and stimulus.video:
            clip = RenderedClip(
                Path(stimulus.video.name).relative_to("stimuli"),
                Path(stimulus.poster.name).relative_to("stimuli"),
                stimulus.duration_ms,
                stimulus.frame_count,
                stimulus.width,
                stimulus.height,
                stimulus.size_bytes,
                stimulus.sha256,
            )
        label = f"{stimulus.condition.key} × {stimulus.item.key}"
        entries.append(Entry(label, ClipSpec.from_dict(stimulus.parameters), clip))
    return entries


def uploaded_manifest(study: Study) -> list[dict]:
    """Return the study's uploaded clips: condition, item, file names, SHA-256s and facts."""
    clips = UploadedClip.objects.filter(condition__study=study).select_related("condition", "item")
    return [
        {
            "label": f"{clip.condition.key} × {clip.item.key}",
            "file": clip.original_name,
            "sha256": clip.sha256,
            "source_sha256": clip.source_sha256,
            "converted": clip.converted,
            "video": clip.video.name,
            "duration_ms": clip.duration_ms,
            "frame_count": clip.frame_count,
            "frame_rate": clip.frame_rate,
            "width": clip.width,
            "height": clip.height,
            "size_bytes": clip.size_bytes,
        }
        for clip in clips.order_by("item__position", "condition__position")
    ]


def group_identical(clips) -> list[tuple[Item, list[Condition]]]:
    """Return each item shown identically in two or more conditions, with those.

    *clips*: (condition, item, content hash) triples; conditions whose specification of
    an item hashes alike render the same pixels.
    """
    by_item: dict[int, tuple[Item, dict[str, list[Condition]]]] = {}
    for condition, item, content_hash in clips:
        hashes = by_item.setdefault(item.pk, (item, {}))[1]
        hashes.setdefault(content_hash, []).append(condition)
    return [
        (item, same)
        for item, hashes in by_item.values()
        for same in hashes.values()
        if len(same) > 1
    ]


def hashed_pairs(pairs: list[tuple[Condition, Item]]) -> list[tuple[Condition, Item, str]]:
    """Return each (condition, item) of *pairs* with its clip's content hash.

    An uploaded clip's hash is its file's SHA-256; one not uploaded yet, and a
    specification that cannot be made, are left out (generation names them).
    """
    uploaded = {(c.pk, i.pk) for c, i in pairs if c.is_uploaded}
    files = {
        (condition, item): sha256
        for condition, item, sha256 in UploadedClip.objects.filter(
            condition__in={c for c, _ in uploaded}
        ).values_list("condition_id", "item_id", "sha256")
    }
    clips = []
    for condition, item in pairs:
        if condition.is_uploaded:
            if (condition.pk, item.pk) in files:
                clips.append((condition, item, files[condition.pk, item.pk]))
            continue
        try:
            clips.append((condition, item, clip_spec(condition, item).content_hash()))
        except ClipError:
            continue
    return clips


def identical_clips(study: Study) -> list[tuple[Item, list[Condition]]]:
    """Return each item whose clips are identical in two or more conditions, with those.

    Two conditions render the same pixels when their clip specifications hash alike
    (e.g. two conditions whose settings differ only in a name).
    """
    return group_identical(hashed_pairs(needed_pairs(study)))


def describe_identical(pairs: list[tuple[Item, list[Condition]]]) -> str:
    """Return one sentence naming the items whose conditions render identical clips."""
    parts = [f"{item.key} ({', '.join(c.key for c in same)})" for item, same in pairs[:5]]
    more = gettext(" and %(count)d more") % {"count": len(pairs) - 5} if len(pairs) > 5 else ""
    return gettext(
        "Conditions render identical clips for %(clips)s: their settings change nothing the "
        "clip shows. Give each condition the technique settings it compares (open the "
        "condition), or confirm that identical clips are intended."
    ) % {"clips": "; ".join(parts) + more}
