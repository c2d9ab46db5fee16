"""Edit questions, their answer options, blocks and trials on pages of their own."""

from django.contrib import admin
from django.http import HttpRequest
from django.utils.translation import gettext

from studyplatform.actions.design import do_add_default_options
from studyplatform.admin.forms import TrialForm
from studyplatform.admin.permissions import DesignLockMixin, StudyScopedMixin
from studyplatform.admin.positions import PositionedFormSet
from studyplatform.admin.prompts import AslVideoInline
from studyplatform.models import AnswerOption, Block, Question, Trial


class OwnStudyFilter(admin.RelatedFieldListFilter):
    """Filter by study, listing only the studies the user may see."""

    def field_choices(self, field, request: HttpRequest, model_admin):
        from studyplatform.admin.permissions import owned_studies

        return [(study.pk, str(study)) for study in owned_studies(request)]


class AnswerOptionInline(DesignLockMixin, admin.TabularInline):
    model = AnswerOption

    def _study_of(self, obj):
        return obj.study  # the inline's parent: the question

    extra = 0
    fields = ("position", "value", "label")
    show_change_link = True
    formset = PositionedFormSet


@admin.register(Question)
class QuestionAdmin(DesignLockMixin, StudyScopedMixin, admin.ModelAdmin):
    list_display = ("key", "kind", "text", "study", "required")
    list_filter = (("study", OwnStudyFilter), "kind", "required")
    search_fields = ("key", "text")
    inlines = (AnswerOptionInline, AslVideoInline)
    fields = (
        "study",
        "position",
        "key",
        "kind",
        "text",
        "help_text",
        "required",
        "allow_no_difference",
        "no_difference_label",
        "allow_signed_answer",
        "is_personal",
        ("min_value", "max_value"),
    )

    def save_related(self, request: HttpRequest, form, formsets, change: bool) -> None:
        super().save_related(request, form, formsets, change)
        added = do_add_default_options(form.instance)
        if added:
            self.message_user(
                request,
                gettext(
                    "“%(key)s” starts with %(count)d labelled points; edit their "
                    "labels below to fit the question."
                )
                % {"key": form.instance.key, "count": added},
            )


@admin.register(AnswerOption)
class AnswerOptionAdmin(DesignLockMixin, StudyScopedMixin, admin.ModelAdmin):
    """Reached from a question's options, to attach an ASL video to one scale point."""

    study_path = "question__study"
    fields = ("question", "position", "value", "label")
    inlines = (AslVideoInline,)

    def has_module_permission(self, request: HttpRequest) -> bool:
        # Options are edited from their question; no entry of their own in the index.
        return False


@admin.register(Block)
class BlockAdmin(DesignLockMixin, StudyScopedMixin, admin.ModelAdmin):
    list_display = ("__str__", "kind", "study", "position", "randomize_order")
    list_filter = (("study", OwnStudyFilter), "kind")
    search_fields = ("key", "title")
    inlines = (AslVideoInline,)


@admin.register(Trial)
class TrialAdmin(DesignLockMixin, StudyScopedMixin, admin.ModelAdmin):
    form = TrialForm
    list_display = (
        "key",
        "kind",
        "block",
        "item",
        "condition_a",
        "condition_b",
        "is_attention_check",
        "study",
    )
    list_filter = (("study", OwnStudyFilter), "kind", "is_attention_check")
    search_fields = ("key", "title", "item__key")
    filter_horizontal = ("questions",)
    inlines = (AslVideoInline,)
    list_select_related = ("block", "item", "condition_a", "condition_b", "study")
