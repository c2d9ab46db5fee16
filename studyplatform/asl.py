"""Find the ASL videos of participant-facing texts, for pages and admin (spec 06 "ASL-first")."""

from dataclasses import dataclass

from django.contrib.contenttypes.models import ContentType
from django.db.models import Q

from studyplatform.models import PARTICIPANT_FACING_FIELDS, AslVideo, Study


@dataclass(frozen=True)
class Prompt:
    """One text participants read, where it is, and its ASL video if there is one."""

    obj: object
    field_name: str
    text: str
    video: AslVideo | None

    @property
    def where(self) -> str:
        model = self.obj._meta.verbose_name
        field = self.obj._meta.get_field(self.field_name).verbose_name
        return f"{model.capitalize()} “{self.obj}” · {field}"

    @property
    def content_type_id(self) -> int:
        return ContentType.objects.get_for_model(self.obj).pk


def asl_videos(objects) -> dict[tuple[str, int, str], AslVideo]:
    """Return the ASL videos of *objects*, by (model name, pk, field name), in one query."""
    by_type: dict[int, list[int]] = {}
    for obj in objects:
        content_type = ContentType.objects.get_for_model(obj)
        by_type.setdefault(content_type.pk, []).append(obj.pk)
    if not by_type:
        return {}
    wanted = Q()
    for type_id, ids in by_type.items():
        wanted |= Q(content_type_id=type_id, object_id__in=ids)
    videos = AslVideo.objects.filter(wanted).select_related("content_type")
    return {(v.content_type.model, v.object_id, v.field_name): v for v in videos}


def study_prompts(study: Study) -> list[Prompt]:
    """Return every non-empty participant-facing text of *study*, in the order met."""
    objects = [study, *study.blocks.all(), *study.trials.select_related("block")]
    for question in study.questions.prefetch_related("options"):
        objects.append(question)
        objects.extend(question.options.all())
    videos = asl_videos(objects)
    prompts = []
    for obj in objects:
        model_name = obj._meta.model_name
        for field_name in PARTICIPANT_FACING_FIELDS[model_name]:
            text = str(getattr(obj, field_name) or "").strip()
            if text:
                video = videos.get((model_name, obj.pk, field_name))
                prompts.append(Prompt(obj, field_name, text, video))
    return prompts
