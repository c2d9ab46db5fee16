"""Attach ASL videos to participant-facing texts."""

from django.contrib.contenttypes.models import ContentType
from django.core.exceptions import ValidationError
from django.core.files import File
from django.db import transaction

from studyplatform.actions.media import delete_unused_files_on_commit
from studyplatform.files.media_types import check_upload, stored_video
from studyplatform.models import PARTICIPANT_FACING_FIELDS, STUDY_PATHS, AslVideo, Study

MAX_ASL_VIDEO_BYTES = 300 * 1024 * 1024


def do_attach_asl_video(
    study: Study, content_type_id: int, object_id: int, field_name: str, upload
) -> AslVideo:
    """Save *upload* as the ASL video of one text of *study*, replacing an older one."""
    try:
        model = ContentType.objects.get_for_id(content_type_id).model_class()
    except ContentType.DoesNotExist:
        raise ValidationError("Unknown kind of text.") from None
    fields = PARTICIPANT_FACING_FIELDS.get(model._meta.model_name if model else "", ())
    if field_name not in fields:
        raise ValidationError(f"“{field_name}” is not a text participants read.")
    path = STUDY_PATHS[model._meta.model_name]
    in_study = {path: study} if path else {"pk": study.pk}
    if not model._default_manager.filter(pk=object_id).filter(**in_study).exists():
        raise ValidationError("This text is not part of the study.")
    name = getattr(upload, "name", "") or "video"
    if upload.size > MAX_ASL_VIDEO_BYTES:
        raise ValidationError("The video is larger than 300 MB.")
    # By content, not by name: MP4 (also .mov, .m4v) or WebM that decodes; stored as such,
    # a camera's WebM with its duration and seek index, named by its content.
    kind = check_upload(upload, ("video",), f"“{name}”")
    with stored_video(upload, kind) as (stored, sha256), transaction.atomic(durable=True):
        video, _ = AslVideo.objects.select_for_update().get_or_create(
            content_type_id=content_type_id,
            object_id=object_id,
            field_name=field_name,
            defaults={"video": ""},
        )
        old = video.video.name if video.video else ""
        video.video.save(f"{sha256}{kind.suffix}", File(stored), save=True)
        if old != video.video.name:
            # A duplicated or imported study's video may be this same file.
            delete_unused_files_on_commit(video.video.storage, [old])
    return video
