"""Find the ASL videos of participant-facing texts, for pages and admin (spec 06 "ASL-first")."""

from dataclasses import dataclass

from django.contrib.contenttypes.models import ContentType
from django.db.models import Q
from django.utils.text import capfirst

from studyplatform.models import PARTICIPANT_FACING_FIELDS, AslVideo, SignedTemplate, Study


@dataclass(frozen=True)
class Prompt:
    """One text participants read, where it is, and its ASL video if there is one."""

    obj: object
    field_name: str
    text: str
    video: AslVideo | SignedTemplate | None

    @property
    def from_template(self) -> bool:
        """Return whether a reusable signed template signs the text."""
        return isinstance(self.video, SignedTemplate)

    @property
    def where(self) -> str:
        model = self.obj._meta.verbose_name
        field = self.obj._meta.get_field(self.field_name).verbose_name
        return f"{capfirst(model)} “{self.obj}” · {field}"

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


# Which template signs which text where the object has no video of its own.
TEMPLATE_FIELDS = {
    ("study", "consent_text"): SignedTemplate.Kind.CONSENT,
    ("study", "thank_you_text"): SignedTemplate.Kind.THANK_YOU,
    ("block", "intro_text"): SignedTemplate.Kind.INSTRUCTIONS,
    ("trial", "text"): SignedTemplate.Kind.INSTRUCTIONS,
}
# Keys of the button templates in a page's videos: ("ui", 0, kind).
UI_KINDS = (SignedTemplate.Kind.NEXT, SignedTemplate.Kind.PREVIOUS, SignedTemplate.Kind.PLAY)


def _is_instructions(obj) -> bool:
    block = obj if obj._meta.model_name == "block" else getattr(obj, "block", None)
    return block is not None and block.kind == "instructions"


def with_templates(videos: dict, study: Study, objects, ui: bool = False) -> dict:
    """Return *videos* with the study's signed templates where a text has none of its own.

    Instructions templates sign only the texts of instructions blocks; with *ui*, the
    button templates are added under ``("ui", 0, kind)``.
    """
    templates = {t.kind: t for t in study.signed_templates.all()}
    if not templates:
        return videos
    videos = dict(videos)
    for obj in objects:
        model_name = obj._meta.model_name
        for field_name in PARTICIPANT_FACING_FIELDS[model_name]:
            kind = TEMPLATE_FIELDS.get((model_name, field_name))
            key = (model_name, obj.pk, field_name)
            if kind is None or key in videos or kind not in templates:
                continue
            if kind == SignedTemplate.Kind.INSTRUCTIONS and not _is_instructions(obj):
                continue
            if str(getattr(obj, field_name) or "").strip():
                videos[key] = templates[kind]
    if ui:
        for kind in UI_KINDS:
            if kind in templates:
                videos[("ui", 0, kind)] = templates[kind]
    return videos


def _shown_fields(obj) -> tuple[str, ...]:
    """Return the participant-facing fields of *obj* that a participant can meet."""
    fields = PARTICIPANT_FACING_FIELDS[obj._meta.model_name]
    if obj._meta.model_name == "question" and not obj.allow_no_difference:
        fields = tuple(f for f in fields if f != "no_difference_label")
    return fields


def study_prompts(study: Study) -> list[Prompt]:
    """Return every non-empty text participants of *study* meet, in the order met.

    Texts nobody sees are left out: blocks without pages, questions no page asks (and
    their options), "Cannot see a difference" where it is not offered.
    """
    trials = list(study.trials.select_related("block").prefetch_related("questions"))
    asked = {q.pk for trial in trials for q in trial.questions.all()}
    shown_blocks = {trial.block_id for trial in trials}
    objects = [study, *(b for b in study.blocks.all() if b.pk in shown_blocks), *trials]
    for question in study.questions.prefetch_related("options"):
        if question.pk in asked:
            objects.append(question)
            if question.uses_options:
                objects.extend(question.options.all())
    videos = with_templates(asl_videos(objects), study, objects)
    prompts = []
    for obj in objects:
        model_name = obj._meta.model_name
        for field_name in _shown_fields(obj):
            text = str(getattr(obj, field_name) or "").strip()
            if text:
                video = videos.get((model_name, obj.pk, field_name))
                prompts.append(Prompt(obj, field_name, text, video))
    return prompts
