"""Validate admin forms beyond what each model checks on its own."""

import json

from django import forms
from django.core.exceptions import ValidationError

from studyplatform.models import Trial


class TrialForm(forms.ModelForm):
    """Edit a trial and check that its questions suit its kind."""

    class Meta:
        model = Trial
        fields = (
            "study",
            "block",
            "position",
            "key",
            "kind",
            "title",
            "text",
            "item",
            "condition_a",
            "condition_b",
            "questions",
            "is_attention_check",
            "expected_answer",
        )

    def clean(self):
        cleaned = super().clean()
        questions = cleaned.get("questions")
        kind = cleaned.get("kind")
        study = cleaned.get("study")
        study_id = study.pk if study is not None else self.instance.study_id
        if questions is not None and kind:
            try:
                Trial(kind=kind, study_id=study_id).check_questions(questions)
            except ValidationError as error:
                self.add_error("questions", error)
        return cleaned


class StudyImportForm(forms.Form):
    """Upload a study definition exported from this or another installation."""

    MAX_BYTES = 5 * 1024 * 1024

    definition = forms.FileField(help_text="A .json file from “Export as JSON”.")
    slug = forms.SlugField(
        required=False,
        max_length=80,
        help_text="Optional. Empty: the file's slug, or a free variant of it.",
    )

    def clean_definition(self):
        upload = self.cleaned_data["definition"]
        if upload.size > self.MAX_BYTES:
            raise ValidationError("The file is larger than 5 MB; a study definition is not.")
        try:
            return json.loads(upload.read().decode("utf-8"))
        except UnicodeDecodeError:
            raise ValidationError("The file is not UTF-8 text.") from None
        except json.JSONDecodeError as error:
            raise ValidationError(
                f"The file is not valid JSON: {error.msg} at line {error.lineno}, "
                f"column {error.colno}."
            ) from None
