"""Researchers' own avatars: upload a GLB or VRM, see what the engine makes of it
(bones, fingers, face channels, preview stills), and map the bones it did not know."""

import json

from django import forms
from django.contrib import admin, messages
from django.db.models import Count
from django.http import HttpRequest
from django.urls import reverse
from django.utils.html import format_html, format_html_join
from django.utils.translation import gettext, gettext_lazy

from studyplatform.actions.avatars import (
    check_avatar_file,
    check_bone_mapping,
    do_map_avatar_bones,
    do_upload_avatar,
)
from studyplatform.admin.permissions import OwnedMixin
from studyplatform.models import Avatar


class AvatarForm(forms.ModelForm):
    """Upload an avatar (a new one) or edit its description and bone mapping."""

    upload = forms.FileField(
        required=False,
        label=gettext_lazy("GLB or VRM file"),
        help_text=gettext_lazy(
            "A humanoid glTF 2.0 binary (.glb) or VRM (.vrm): a skeleton with skin "
            "weights; finger bones to fingerspell; ARKit-named morph targets or VRM "
            "expressions for the face. At most 200 MB."
        ),
    )

    class Meta:
        model = Avatar
        fields = ("name", "licence", "source", "bone_mapping")

    def __init__(self, *args, **kwargs):
        super().__init__(*args, **kwargs)
        self.fields["name"].required = False
        if self.instance.pk is None:
            self.fields["upload"].required = True
            self.fields.pop("bone_mapping", None)

    def clean_upload(self):
        upload = self.cleaned_data.get("upload")
        if upload is not None:
            check_avatar_file(upload)  # AvatarRejected is the field's error
        return upload

    def clean_bone_mapping(self):
        value = self.cleaned_data.get("bone_mapping") or {}
        check_bone_mapping(self.instance, value)
        return value


@admin.register(Avatar)
class AvatarAdmin(OwnedMixin, admin.ModelAdmin):
    """A researcher's avatars; each sees and uses only their own."""

    form = AvatarForm
    list_display = ("name", "licence", "status", "body", "fingers", "face", "condition_count")
    list_filter = ("status",)
    search_fields = ("name", "source")
    readonly_fields = ("stills", "findings", "status", "error", "sha256", "original_name")

    def get_fieldsets(self, request: HttpRequest, obj=None):
        if obj is None:
            return [(None, {"fields": ("upload", "name", "licence", "source")})]
        return [
            (None, {"fields": ("stills", "name", "licence", "source", "status", "error")}),
            (gettext("What the engine found"), {"fields": ("findings", "bone_mapping")}),
            (gettext("File"), {"fields": ("original_name", "sha256")}),
        ]

    def get_queryset(self, request: HttpRequest):
        queryset = super().get_queryset(request).annotate(_conditions=Count("conditions"))
        return queryset if request.user.is_superuser else queryset.filter(owner=request.user)

    def save_model(self, request: HttpRequest, obj: Avatar, form, change: bool) -> None:
        """Store a new upload through its action; save a new mapping into the file."""
        data = form.cleaned_data
        if not change:
            created = do_upload_avatar(
                request.user,
                data["upload"],
                data.get("name") or "",
                data["licence"],
                data.get("source") or "",
            )
            obj.pk, obj.file = created.pk, created.file
            return
        stored = Avatar.objects.get(pk=obj.pk)
        super().save_model(request, obj, form, change)
        if (data.get("bone_mapping") or {}) != (stored.bone_mapping or {}):
            do_map_avatar_bones(obj, data["bone_mapping"])
            messages.info(
                request,
                gettext(
                    "The mapping is saved in the file; clips filmed with the "
                    "avatar will be rendered again."
                ),
            )

    @admin.display(description=gettext_lazy("signs"))
    def body(self, avatar: Avatar) -> bool:
        return avatar.signs

    @admin.display(description=gettext_lazy("fingerspells"))
    def fingers(self, avatar: Avatar) -> bool:
        return avatar.fingerspells

    @admin.display(description=gettext_lazy("face channels"))
    def face(self, avatar: Avatar) -> int:
        return len(avatar.report.get("face_channels", []))

    @admin.display(description=gettext_lazy("conditions"), ordering="_conditions")
    def condition_count(self, avatar: Avatar) -> int:
        return avatar._conditions

    @admin.display(description=gettext_lazy("previews"))
    def stills(self, avatar: Avatar) -> str:
        if avatar.status != Avatar.Status.READY:
            return (
                gettext("Being rendered; reload the page.") if avatar.status == "preparing" else "—"
            )
        return format_html_join(
            " ",
            '<figure style="display:inline-block;margin:0 8px 0 0"><img src="{}" '
            'width="240" alt="{}"><figcaption>{}</figcaption></figure>',
            (
                (reverse("private_media", args=[field.name]), label, label)
                for field, label in (
                    (avatar.still_rest, gettext("at rest")),
                    (avatar.still_letter, gettext("the letter B")),
                    (avatar.still_face, gettext("brows raised (a question)")),
                )
            ),
        )

    @admin.display(description=gettext_lazy("bones and face"))
    def findings(self, avatar: Avatar) -> str:
        report = avatar.report or {}
        missing = report.get("missing_fingers") or {}
        hands = "; ".join(
            gettext("%(side)s hand: all finger bones") % {"side": side}
            if not names
            else gettext("%(side)s hand: lacks %(bones)s")
            % {"side": side, "bones": ", ".join(names)}
            for side, names in missing.items()
        )
        channels = report.get("face_channels") or []
        face = (
            gettext("plays %(count)d channels (%(names)s)")
            % {
                "count": len(channels),
                "names": ", ".join(channels[:8]) + ("…" if len(channels) > 8 else ""),
            }
            if channels
            else gettext(
                "no morph target the face channels drive (ARKit names or VRM expressions): "
                "non-manual signals are not shown"
            )
        )
        body = report.get("missing_body") or []
        warning = (
            format_html(
                '<strong class="errornote">{}</strong><br>',
                gettext(
                    "Not mapped, so they stay as the avatar was modelled while the rest "
                    "signs (a T-pose's arms held out): %(bones)s. Map these bones below."
                )
                % {"bones": ", ".join(body)},
            )
            if body
            else ""
        )
        return format_html(
            "{}{}<br>{}.<br>{}<br>{}<br><details><summary>{}</summary><pre>{}</pre></details>",
            warning,
            gettext(
                "%(mapped)d of %(joints)d joints mapped to the engine's; not mapped: %(unmapped)s."
            )
            % {
                "mapped": len(report.get("mapped", {})),
                "joints": report.get("joints", 0),
                "unmapped": ", ".join(report.get("unmapped", [])) or gettext("none"),
            },
            hands,
            gettext("Face: %(face)s.") % {"face": face},
            gettext("Height %(height)s m.") % {"height": report.get("height_m")},
            gettext("The mapping"),
            json.dumps(report.get("mapped", {}), indent=1),
        )
