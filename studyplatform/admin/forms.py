"""Validate admin forms beyond what each model checks on its own."""

from django import forms
from django.core.exceptions import ValidationError
from django.utils.translation import gettext, gettext_lazy, ngettext

from studyplatform.lib import strict_json
from studyplatform.lib.bundle import BundleRejected, read_bundle
from studyplatform.models import Study, Trial


class StudyForm(forms.ModelForm):
    """Edit a study; refuse to let participants in while conditions show identical clips."""

    class Meta:
        model = Study
        fields = ("status", "allow_identical_clips")  # the admin adds its fieldsets

    def clean(self):
        cleaned = super().clean()
        study = self.instance
        backward = cleaned.get("status") in (Study.Status.DRAFT, Study.Status.PILOT)
        if backward and study.real_participants:
            self.add_error(
                "status",
                ngettext(
                    "%(count)d participant has taken this study (pilots aside), so it cannot "
                    "go back to draft or pilot: their answers refer to its design. Close it, "
                    "or make a new version of the study to change it.",
                    "%(count)d participants have taken this study (pilots aside), so it "
                    "cannot go back to draft or pilot: their answers refer to its design. "
                    "Close it, or make a new version of the study to change it.",
                    study.real_participants,
                )
                % {"count": study.real_participants},
            )
        opening = cleaned.get("status") in (Study.Status.PILOT, Study.Status.OPEN)
        was_closed = study.pk is None or study.status in (Study.Status.DRAFT, Study.Status.CLOSED)
        if study.pk and opening and was_closed and not cleaned.get("allow_identical_clips"):
            from studyplatform.lib.stimuli import describe_identical, identical_clips

            identical = identical_clips(study)
            if identical:
                self.add_error(
                    "status",
                    gettext("%(identical)s (tick “identical clips intended” below).")
                    % {"identical": describe_identical(identical)},
                )
        return cleaned


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
    MAX_BUNDLE_BYTES = 1024 * 1024 * 1024

    definition = forms.FileField(
        label=gettext_lazy("Definition"),
        help_text=gettext_lazy(
            "A .json file from “Export as JSON”, or a .zip from “Export with media”."
        ),
    )
    slug = forms.SlugField(
        label=gettext_lazy("Slug"),
        required=False,
        max_length=80,
        help_text=gettext_lazy("Optional. Empty: the file's slug, or a free variant of it."),
    )

    def clean_definition(self):
        """Return (definition, files by media name) from the JSON or zip upload."""
        upload = self.cleaned_data["definition"]
        head = upload.read(4)
        upload.seek(0)
        if head == b"PK\x03\x04":
            if upload.size > self.MAX_BUNDLE_BYTES:
                raise ValidationError(gettext("The bundle is larger than 1 GB."))
            try:
                return read_bundle(upload)  # read while the import runs
            except BundleRejected as error:
                raise ValidationError(
                    gettext("The file is %(problem)s.") % {"problem": error}
                ) from None
        if upload.size > self.MAX_BYTES:
            raise ValidationError(
                gettext("The file is larger than 5 MB; a study definition is not.")
            )
        try:
            return strict_json.loads(upload.read()), {}
        except strict_json.JsonRejected as error:
            raise ValidationError(
                gettext("The file is %(problem)s.") % {"problem": error}
            ) from None


class ResultsForm(forms.Form):
    """Choose exclusions and test options for a study's results page (a GET form)."""

    applied = forms.BooleanField(widget=forms.HiddenInput, initial=True, required=False)
    exclude_pilot = forms.BooleanField(
        required=False, initial=True, label=gettext_lazy("Exclude pilot")
    )
    exclude_failed_attention = forms.BooleanField(
        required=False, initial=True, label=gettext_lazy("Exclude failed attention checks")
    )
    exclude_incomplete = forms.BooleanField(
        required=False, initial=True, label=gettext_lazy("Exclude incomplete sessions")
    )
    exclude_early_answers = forms.BooleanField(
        required=False,
        initial=False,
        label=gettext_lazy("Exclude participants who answered before the clips ended"),
    )
    min_median_page_s = forms.FloatField(
        required=False,
        min_value=0,
        label=gettext_lazy("Exclude participants whose median time on a page is under (s)"),
        help_text=gettext_lazy("Empty: no limit."),
        widget=forms.NumberInput(attrs={"step": "0.5", "style": "width: 5em"}),
    )
    ties = forms.ChoiceField(
        choices=[
            ("exclude", gettext_lazy("excluded from tests")),
            ("split", gettext_lazy("split across the pair")),
        ],
        initial="exclude",
        label=gettext_lazy("“Cannot see a difference”"),
    )
    correction = forms.ChoiceField(
        choices=[
            ("holm", "Holm"),
            ("bonferroni", "Bonferroni"),
            ("fdr_bh", "Benjamini–Hochberg"),
            ("none", gettext_lazy("none")),
        ],
        initial="holm",
        label=gettext_lazy("Multiple comparisons"),
    )

    def __init__(self, data, *, demographic_questions):
        # Unsubmitted: start from the initial values (a GET form has no "unchecked").
        if not data or "applied" not in data:
            data = None
        super().__init__(data)
        self.demographic_fields = []
        for question in demographic_questions:
            options = [o.label or str(o.value) for o in question.options.all()]
            if not options:
                continue
            name = f"only_{question.key}"
            self.fields[name] = forms.MultipleChoiceField(
                choices=[(label, label) for label in options],
                required=False,
                widget=forms.CheckboxSelectMultiple,
                label=gettext("Only participants whose %(key)s is") % {"key": question.key},
                help_text=gettext("None ticked: no filter."),
            )
            self.demographic_fields.append((name, question.key))

    def options(self):
        """Return the ReportOptions the form describes (its initial values if unbound)."""
        from analysis import ExclusionRules, ReportOptions

        values = (
            self.cleaned_data
            if self.is_bound and self.is_valid()
            else {name: field.initial for name, field in self.fields.items()}
        )
        keep_only = {
            key: tuple(values.get(name) or ())
            for name, key in self.demographic_fields
            if values.get(name)
        }
        return ReportOptions(
            tie_handling=values["ties"],
            correction=values["correction"],
            exclusions=ExclusionRules(
                pilot=bool(values["exclude_pilot"]),
                failed_attention=bool(values["exclude_failed_attention"]),
                incomplete=bool(values["exclude_incomplete"]),
                keep_only=keep_only,
                answered_before_end=bool(values["exclude_early_answers"]),
                min_median_page_s=values["min_median_page_s"],
            ),
        )
