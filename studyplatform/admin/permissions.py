"""Limit every admin page to the studies of the researcher looking at it.

Superusers see everything. Any other staff user sees, in every list, form choice and
URL, only objects that belong to studies they own; another researcher's objects are
treated as if they did not exist.
"""

from django.contrib import admin
from django.db.models import Model, QuerySet
from django.http import HttpRequest

from studyplatform.admin.positions import PositionedFormSet
from studyplatform.models import STUDY_PATHS, Study

# The attribute of the request on which an inline finds the study being edited; admin
# instances are shared between threads, so per-request state lives on the request.
PARENT_STUDY_ATTRIBUTE = "_signstudy_parent_study"


def owned_studies(request: HttpRequest) -> QuerySet[Study]:
    """Return the studies the request's user may see."""
    if request.user.is_superuser:
        return Study.objects.all()
    return Study.objects.filter(owner=request.user)


def scope_queryset(queryset: QuerySet, study_path: str, request: HttpRequest) -> QuerySet:
    """Filter *queryset* to objects whose *study_path* leads to a study the user owns."""
    if request.user.is_superuser:
        return queryset
    owner_lookup = "owner" if study_path == "" else f"{study_path}__owner"
    return queryset.filter(**{owner_lookup: request.user})


def scope_related(queryset: QuerySet, request: HttpRequest) -> QuerySet:
    """Filter a form's choice list to objects of the user's (or the edited) study."""
    model_name = queryset.model._meta.model_name
    if model_name not in STUDY_PATHS:
        return queryset
    path = STUDY_PATHS[model_name]
    parent = getattr(request, PARENT_STUDY_ATTRIBUTE, None)
    if parent is not None and parent.pk is None:
        return queryset.none()
    if parent is not None and path:
        return queryset.filter(**{path: parent})
    if parent is not None:
        return queryset.filter(pk=parent.pk)
    return scope_queryset(queryset, path, request)


class StudyScopedMixin:
    """Restrict an admin (or inline) to the user's own studies.

    Set ``study_path`` to the lookup from the model to its Study ("" for Study itself).
    """

    study_path = "study"

    def get_queryset(self, request: HttpRequest) -> QuerySet:
        return scope_queryset(super().get_queryset(request), self.study_path, request)

    def _study_of(self, obj: Model) -> Study | None:
        study = obj
        for part in filter(None, self.study_path.split("__")):
            study = getattr(study, part)
        return study

    def _owns(self, request: HttpRequest, obj: Model | None) -> bool:
        if obj is None or request.user.is_superuser:
            return True
        study = self._study_of(obj)
        return study is None or study.owner_id == request.user.pk

    def get_form(self, request: HttpRequest, obj: Model | None = None, **kwargs):
        # On an existing object's page, offer only choices from that object's study.
        if obj is not None:
            setattr(request, PARENT_STUDY_ATTRIBUTE, self._study_of(obj))
        return super().get_form(request, obj, **kwargs)

    def has_view_permission(self, request: HttpRequest, obj: Model | None = None) -> bool:
        return super().has_view_permission(request, obj) and self._owns(request, obj)

    def has_change_permission(self, request: HttpRequest, obj: Model | None = None) -> bool:
        return super().has_change_permission(request, obj) and self._owns(request, obj)

    def has_delete_permission(self, request: HttpRequest, obj: Model | None = None) -> bool:
        return super().has_delete_permission(request, obj) and self._owns(request, obj)

    def formfield_for_foreignkey(self, db_field, request: HttpRequest, **kwargs):
        formfield = super().formfield_for_foreignkey(db_field, request, **kwargs)
        if formfield is not None and hasattr(formfield, "queryset"):
            formfield.queryset = scope_related(formfield.queryset, request)
        return formfield

    def formfield_for_manytomany(self, db_field, request: HttpRequest, **kwargs):
        formfield = super().formfield_for_manytomany(db_field, request, **kwargs)
        if formfield is not None and hasattr(formfield, "queryset"):
            formfield.queryset = scope_related(formfield.queryset, request)
        return formfield


class StudyInline(StudyScopedMixin, admin.TabularInline):
    """A tabular inline on the study page whose choices come from that study only; new
    rows are numbered after the others (PositionedFormSet)."""

    extra = 0
    show_change_link = True
    formset = PositionedFormSet

    def _study_of(self, obj: Model) -> Study | None:
        # An inline's permission checks receive the parent study itself.
        return obj

    def get_formset(self, request: HttpRequest, obj: Study | None = None, **kwargs):
        # Choice fields are built inside super().get_formset(); they read the parent
        # study from the request. A study not yet saved has nothing to choose from.
        setattr(request, PARENT_STUDY_ATTRIBUTE, obj if obj is not None else Study())
        return super().get_formset(request, obj, **kwargs)

    def has_add_permission(self, request: HttpRequest, obj: Study | None = None) -> bool:
        return super().has_add_permission(request, obj) and self._owns(request, obj)


class DesignLockMixin:
    """Show a study's design read-only once the study is open or closed.

    For an admin of a design object (condition, item, question, option, block, trial)
    or an inline of one; an inline's permission checks receive its parent object.
    """

    def _design_locked(self, obj: Model | None) -> bool:
        study = self._study_of(obj) if obj is not None else None
        return study is not None and study.design_locked

    def has_add_permission(self, request: HttpRequest, obj: Model | None = None) -> bool:
        if self._design_locked(obj):
            return False
        if isinstance(self, admin.options.InlineModelAdmin):
            return super().has_add_permission(request, obj)
        return super().has_add_permission(request)

    def has_change_permission(self, request: HttpRequest, obj: Model | None = None) -> bool:
        return super().has_change_permission(request, obj) and not self._design_locked(obj)

    def has_delete_permission(self, request: HttpRequest, obj: Model | None = None) -> bool:
        return super().has_delete_permission(request, obj) and not self._design_locked(obj)


class OwnedMixin:
    """Limit a researcher's library (signed templates, avatars) to its owner's rows:
    listed, viewed, changed and deleted by them alone (a superuser sees all)."""

    def _own(self, request: HttpRequest, obj) -> bool:
        return obj is None or request.user.is_superuser or obj.owner_id == request.user.pk

    def has_view_permission(self, request: HttpRequest, obj=None) -> bool:
        return super().has_view_permission(request, obj) and self._own(request, obj)

    def has_change_permission(self, request: HttpRequest, obj=None) -> bool:
        return super().has_change_permission(request, obj) and self._own(request, obj)

    def has_delete_permission(self, request: HttpRequest, obj=None) -> bool:
        return super().has_delete_permission(request, obj) and self._own(request, obj)
