"""Sign the ASL-first demo's prompts with the platform's own avatar, labelled as such.

A newcomer should see what an ASL-first study looks like: a signed prompt above its
English text, "Hide English text" hiding only the English of signed texts, and "English
only". A real study's prompts are signed by a human signer (uploaded or recorded in the
admin); the demo has none, so the avatar signs short glosses of some of its texts from
the sign library and fingerspelling (synthesis.signing), and every video says under it
that it is avatar-signed demo material. The others stay in English only, so the demo
also shows what a text without a video looks like.
"""

import re
from typing import Any

from synthesis.signing.stories import DEMO_PROMPTS

# Shown under each video whatever the language setting (AslVideo.credit).
CREDIT = "Avatar-signed demo material (the platform's avatar, not a human signer)"
# The spine study's signed texts: (model, key or None for the study, field, gloss). The
# glosses use the sign library's signs and fingerspell the rest; the markers are its
# non-manual signals (whq: wh-question brows).
SPINE_PROMPTS: tuple[tuple[str, str | None, str, str], ...] = (
    ("study", None, "consent_text", DEMO_PROMPTS["consent"]),
    ("question", "clarity", "text", DEMO_PROMPTS["clarity"]),
    ("question", "naturalness", "text", DEMO_PROMPTS["naturalness"]),
    ("question", "preferred", "text", DEMO_PROMPTS["preferred"]),
    ("study", None, "thank_you_text", DEMO_PROMPTS["thank you"]),
)
# The prompts are signed as the study's sentences are, spine on, smaller and at 30 fps.
CLIP = {"spine": True, "rate_hz": 30.0, "width": 480, "height": 360, "seed": 1}


def transcript(gloss: str) -> str:
    """Return the caption of a signed gloss: its signs, without the non-manual markers."""
    from synthesis.signing.nonmanual import parse_spans

    signs = re.sub(r"\s+([,.?!])", r"\1", parse_spans(gloss)[0])
    return f"Gloss: {' '.join(signs.split())}"


def _target(study, model: str, key: str | None) -> Any:
    if model == "study":
        return study
    if model == "question":
        return study.questions.get(key=key)
    raise ValueError(f"no signed demo prompt on a {model}")


def sign_prompts(study, prompts=SPINE_PROMPTS) -> int:
    """Render and attach the avatar-signed *prompts* of *study*; return how many were new.

    Each clip is content-addressed in the clips folder like a stimulus (rendered once,
    whichever database asks); texts that already have a video keep it.
    """
    from django.contrib.contenttypes.models import ContentType
    from django.core.files import File

    from stimuli.clips import ClipSpec, render
    from studyplatform.actions import do_attach_asl_video
    from studyplatform.lib.stimuli import clips_folder
    from studyplatform.models import AslVideo
    from synthesis.techniques import ClipRequest

    attached = 0
    for model, key, field_name, gloss in prompts:
        target = _target(study, model, key)
        content_type = ContentType.objects.get_for_model(target)
        lookup = {"content_type": content_type, "object_id": target.pk, "field_name": field_name}
        if AslVideo.objects.filter(**lookup).exists():
            continue
        request = ClipRequest.from_parameters("sentence", gloss, CLIP)
        clip = render(ClipSpec.from_request(request), clips_folder())
        with open(clip.video, "rb") as handle:
            video = do_attach_asl_video(
                study,
                content_type.pk,
                target.pk,
                field_name,
                File(handle, name=f"{clip.video.stem}.mp4"),
            )
        with open(clip.poster, "rb") as handle:
            video.poster.save(f"{clip.poster.stem}.png", File(handle), save=False)
        video.transcript = transcript(gloss)
        video.credit = CREDIT
        video.save(update_fields=["poster", "transcript", "credit"])
        attached += 1
    return attached
