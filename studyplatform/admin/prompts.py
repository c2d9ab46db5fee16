"""Attach ASL videos to participant-facing text from the admin."""

from django import forms
from django.contrib.contenttypes.admin import GenericTabularInline

from studyplatform.models import PARTICIPANT_FACING_FIELDS, AslVideo


class AslVideoInline(GenericTabularInline):
    """Upload the ASL versions of an object's texts, one per text field."""

    model = AslVideo
    extra = 0
    fields = ("field_name", "video", "poster", "transcript")
    verbose_name = "ASL video"
    verbose_name_plural = "ASL videos of these texts"

    def get_formset(self, request, obj=None, **kwargs):
        model_name = self.parent_model._meta.model_name
        choices = [
            (name, self.parent_model._meta.get_field(name).verbose_name.capitalize())
            for name in PARTICIPANT_FACING_FIELDS[model_name]
        ]
        kwargs["form"] = type(
            "AslVideoForm",
            (forms.ModelForm,),
            {"field_name": forms.ChoiceField(choices=choices, label="Text")},
        )
        return super().get_formset(request, obj, **kwargs)
