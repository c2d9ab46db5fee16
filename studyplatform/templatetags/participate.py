"""Template helpers of the participant pages: ASL prompt videos, time left."""

from django import template
from django.utils.translation import gettext, ngettext

register = template.Library()


@register.simple_tag
def asl_video(videos: dict, obj, field_name: str):
    """Return the ASL video signing *obj*'s *field_name*, or None (``{% asl_video … as v %}``)."""
    if obj is None or not videos:
        return None
    return videos.get((obj._meta.model_name, obj.pk, field_name))


@register.simple_tag
def ui_video(videos: dict, kind: str):
    """Return the signed template of a button (``{% ui_video asl "next" as v %}``), or None."""
    return (videos or {}).get(("ui", 0, kind))


@register.filter
def get_item(mapping: dict, key: str):
    """Return ``mapping[key]`` or "" (for per-question error messages)."""
    return (mapping or {}).get(key, "")


@register.filter
def minutes_left(seconds: int) -> str:
    """Say how long is left in whole minutes ("12 minutes left"), as the page's timer does."""
    minutes = int(seconds) // 60
    if minutes < 1:
        return gettext("Less than a minute left")
    return ngettext("%(minutes)s minute left", "%(minutes)s minutes left", minutes) % {
        "minutes": minutes
    }
