"""Edit a condition through fields generated from the technique registry, never raw JSON.

Each technique that applies to the study's item kinds gets a fieldset: one form field
per parameter, with its type, allowed values or range, default and help text. What the
researcher leaves at the default is not stored, so a condition's parameters say only
what it changes; anything the registry does not know stays in "Other parameters" where
the model's check names it.
"""

from django import forms
from django.contrib import admin
from django.http import HttpRequest
from django.utils.html import escape, format_html
from django.utils.translation import gettext, gettext_lazy

from studyplatform.admin.design import OwnStudyFilter
from studyplatform.admin.permissions import DesignLockMixin, StudyScopedMixin
from studyplatform.lib.engine_texts import parameter_title
from studyplatform.models import Condition
from studyplatform.rules import (
    condition_item_kinds,
    describe_condition,
    file_help,
    study_values,
    supported_kinds,
)
from synthesis.techniques import REGISTRY, REQUEST_PARAMETERS, Parameter

PREFIX = "technique_"
ADMIN_HIDDEN = frozenset({"avatar_file"})
# A condition is filmed like the others of its item; the seed is the item's (shared
# performance), so it is set on items, not here.
FILMING = tuple(p for p in REQUEST_PARAMETERS if p.name != "seed")


def parameter_formfield(parameter: Parameter, initial) -> forms.Field:
    """Return the form field that edits *parameter*, showing *initial*."""
    # The engine's texts, translated through the catalogues (studyplatform.lib.engine_texts),
    # and escaped: the admin shows help as HTML, where "recording:<id>" lost its "<id>".
    help_text = escape(gettext(parameter.help))
    common = {"label": gettext(parameter_title(parameter)), "initial": initial}
    if parameter.type == "choice":
        labels = parameter.labels or {}
        choices = [(value, gettext(labels.get(value, value))) for value in parameter.choices]
        return forms.ChoiceField(choices=choices, help_text=help_text, **common)
    if parameter.type == "bool":
        return forms.TypedChoiceField(
            choices=[(True, gettext_lazy("On")), (False, gettext_lazy("Off"))],
            coerce=lambda v: v in (True, "True"),
            help_text=help_text,
            **common,
        )
    if parameter.type == "file":
        help_text += escape(f" {file_help(parameter.name)}")
        return forms.CharField(required=False, help_text=help_text, **common)
    field = forms.IntegerField if parameter.type == "int" else forms.FloatField
    default = value_text(parameter, parameter.default)
    return field(
        min_value=parameter.minimum,
        max_value=parameter.maximum,
        help_text=escape(gettext("%(help)s Default: %(default)s."))
        % {"help": help_text, "default": escape(default)},
        **common,
    )


def english_description(condition: Condition) -> str:
    """Return :func:`~studyplatform.rules.describe_condition` marked as English for a page
    in another language: the engine's own wording, as the report's methods section uses."""
    return format_html('<span lang="en">{}</span>', describe_condition(condition))


def value_text(parameter: Parameter, value) -> str:
    """Return *value* of *parameter* in words, in the researcher's language."""
    if parameter.type == "choice":
        return gettext((parameter.labels or {}).get(value, str(value)))
    if parameter.type == "bool":
        return gettext("On") if value else gettext("Off")
    if parameter.type in ("int", "float"):
        units = f" {gettext(parameter.units)}" if parameter.units else ""
        return f"{value:g}{units}"
    return str(value) if value else "—"


def technique_groups(kinds) -> list[tuple[str, tuple[Parameter, ...]]]:
    """Return (fieldset title, parameters) for the techniques of *kinds*, then filming."""
    kinds = supported_kinds(kinds) or list(REGISTRY.kinds)
    groups, seen = [], set()
    for technique in REGISTRY.techniques:
        if technique.kinds & set(kinds) and technique.name not in seen:
            seen.add(technique.name)
            label = gettext(technique.label)
            title = f"{label} ({technique.source})" if technique.source else label
            # An imported avatar is chosen from the researcher's Avatars (the condition's
            # avatar field), not typed as a path.
            shown = tuple(p for p in technique.parameters if p.name not in ADMIN_HIDDEN)
            groups.append((title, shown))
    groups.append((gettext_lazy("Filming"), FILMING))
    return groups


# Every parameter a condition page may show, by name.
_PARAMETERS = {
    parameter.name: parameter
    for parameter in (*(p for t in REGISTRY.techniques for p in t.parameters), *FILMING)
    if parameter.name not in ADMIN_HIDDEN
}


class ConditionForm(forms.ModelForm):
    """Edit a condition; the technique fields are added per study by :func:`condition_form`."""

    groups: list = []

    class Meta:
        model = Condition
        fields = (
            "study",
            "position",
            "key",
            "label",
            "description",
            "source",
            "avatar",
            "is_simulated",
            "parameters",
        )
        labels = {"parameters": gettext_lazy("Other parameters (JSON)")}
        help_texts = {
            "parameters": gettext_lazy(
                "Settings no field above offers; normally empty {}. Checked on save against "
                "the parameters' JSON Schema (linked from Import study)."
            )
        }

    def __init__(self, *args, **kwargs) -> None:
        super().__init__(*args, **kwargs)
        stored = dict(self.instance.parameters or {})
        study = self.instance.study if self.instance.study_id is not None else None
        defaults = study_values(study)
        for _, parameters in self.groups:
            for parameter in parameters:
                field = self.fields[PREFIX + parameter.name]
                default = defaults.get(parameter.name, parameter.default)
                field.initial = stored.pop(parameter.name, default)
        self.initial["parameters"] = stored

    def clean(self):
        cleaned = super().clean()
        extra = cleaned.get("parameters")
        if extra is None or isinstance(extra, dict):
            parameters = dict(extra or {})
            # What the study sets for its items (its alphabet) is a default here too.
            defaults = study_values(cleaned.get("study"))
            for _, declared in self.groups:
                for parameter in declared:
                    value = cleaned.get(PREFIX + parameter.name)
                    default = defaults.get(parameter.name, parameter.default)
                    # A default (or an empty file) is not stored: it says nothing.
                    if value not in (None, "", default):
                        parameters[parameter.name] = value
        else:
            parameters = extra  # not a mapping: the model's check names what is wrong
        cleaned["parameters"] = parameters
        self.instance.parameters = parameters
        return cleaned


def condition_form(kinds) -> type[ConditionForm]:
    """Return a condition form with a field per technique parameter of *kinds*."""
    groups = technique_groups(kinds)
    fields = {
        PREFIX + parameter.name: parameter_formfield(parameter, parameter.default)
        for _, parameters in groups
        for parameter in parameters
    }
    return type("ConditionForm", (ConditionForm,), {**fields, "groups": groups})


@admin.register(Condition)
class ConditionAdmin(DesignLockMixin, StudyScopedMixin, admin.ModelAdmin):
    list_display = ("label", "key", "study", "source", "is_simulated", "compares")
    list_filter = (("study", OwnStudyFilter), "source", "is_simulated")
    search_fields = ("key", "label")
    readonly_fields = ("compares",)

    def get_form(self, request: HttpRequest, obj: Condition | None = None, **kwargs):
        kwargs["form"] = condition_form(condition_item_kinds(obj))
        return super().get_form(request, obj, **kwargs)

    def get_fieldsets(self, request: HttpRequest, obj: Condition | None = None):
        main = (
            "study",
            "position",
            "key",
            "label",
            "description",
            "source",
            "avatar",
            "is_simulated",
            "compares",
        )
        fieldsets = [(None, {"fields": main})]
        for title, parameters in technique_groups(condition_item_kinds(obj)):
            fieldsets.append((title, {"fields": [PREFIX + p.name for p in parameters]}))
        fieldsets.append(
            (gettext("Other parameters"), {"fields": ["parameters"], "classes": ["collapse"]})
        )
        return fieldsets

    @admin.display(description=gettext_lazy("What it compares"))
    def compares(self, obj: Condition) -> str:
        return english_description(obj)

    def __getattr__(self, name: str):
        # A locked design's condition page is read-only: Django makes no form then and
        # looks each technique field up on the admin, so it is answered here with the
        # parameter's value in words (else every field would read "None").
        parameter = _PARAMETERS.get(name.removeprefix(PREFIX)) if name.startswith(PREFIX) else None
        if parameter is None:
            raise AttributeError(name)

        @admin.display(description=gettext_lazy(parameter_title(parameter)))
        def value(condition: Condition) -> str:
            values = {**study_values(condition.study), **(condition.parameters or {})}
            return value_text(parameter, values.get(parameter.name, parameter.default))

        return value

    def formfield_for_foreignkey(self, db_field, request: HttpRequest, **kwargs):
        if db_field.name == "avatar" and not request.user.is_superuser:
            from studyplatform.models import Avatar

            kwargs["queryset"] = Avatar.objects.filter(owner=request.user)
        return super().formfield_for_foreignkey(db_field, request, **kwargs)
