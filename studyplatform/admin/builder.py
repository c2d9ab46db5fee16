"""The design builder: pick conditions × items and a design; the trials are made for you."""

from django import forms
from django.contrib import messages
from django.http import HttpRequest, HttpResponse
from django.shortcuts import redirect
from django.urls import path, reverse
from django.utils.translation import gettext, gettext_lazy

from stimuli.plan import Design, DesignError, DesignSpec
from studyplatform.actions.design import DesignRejected, do_build_design
from studyplatform.actions.versions import do_create_study_version
from studyplatform.lib.design import ANSWER_S, INFO_PAGE_S, summarize_design
from studyplatform.lib.uploads import mismatched_pairs
from studyplatform.models import Study, Trial
from studyplatform.questions import QUESTION_TYPES, question_type


def builder_question_kinds(trial_kinds=Trial.TWO_CLIP_KINDS | Trial.ONE_CLIP_KINDS) -> list[str]:
    """Return the registered question kinds a page of clips among *trial_kinds* may ask."""
    return [kind for kind, type_ in QUESTION_TYPES.items() if type_.trial_kinds & trial_kinds]


def _questions_help() -> str:
    pages = "; ".join(
        f"{str(Trial.Kind(kind).label).lower()}: "
        + ", ".join(str(question_type(k).label) for k in builder_question_kinds(frozenset({kind})))
        for kind in sorted(Trial.TWO_CLIP_KINDS) + sorted(Trial.ONE_CLIP_KINDS)
    )
    return gettext(
        "What each page asks, questions one kind of page may ask together (%(pages)s). "
        "None chosen: a standard question is created (“Which clip looks more natural?”, "
        "or a 5-point naturalness rating)."
    ) % {"pages": pages}


class DesignForm(forms.Form):
    """Choose the design, its conditions and items, practice, questions and checks."""

    design = forms.ChoiceField(
        label=gettext_lazy("Design"),
        choices=[(d.value, gettext_lazy(d.label)) for d in Design],
        widget=forms.RadioSelect,
        initial=Design.BALANCED_PAIRS.value,
    )
    conditions = forms.ModelMultipleChoiceField(
        label=gettext_lazy("Conditions"),
        queryset=None,
        widget=forms.CheckboxSelectMultiple,
        help_text=gettext_lazy("The conditions compared (add them on the study page first)."),
    )
    items = forms.ModelMultipleChoiceField(
        label=gettext_lazy("Items"),
        queryset=None,
        widget=forms.CheckboxSelectMultiple,
        help_text=gettext_lazy("The items shown in every condition."),
    )
    practice_items = forms.ModelMultipleChoiceField(
        label=gettext_lazy("Practice items"),
        queryset=None,
        required=False,
        widget=forms.CheckboxSelectMultiple,
        help_text=gettext_lazy(
            "One practice page each, before the trials; practice answers are not analysed."
        ),
    )
    questions = forms.ModelMultipleChoiceField(
        label=gettext_lazy("Questions"),
        queryset=None,
        required=False,
        widget=forms.CheckboxSelectMultiple,
    )
    attention_checks = forms.IntegerField(
        label=gettext_lazy("Attention checks"),
        min_value=0,
        max_value=20,
        initial=1,
        help_text=gettext_lazy(
            "Pages with a known answer, flagged in the data: two identical clips on pair "
            "designs (answer: no difference), an instructed answer on rating designs."
        ),
    )
    randomize_order = forms.BooleanField(
        required=False,
        initial=True,
        label=gettext_lazy("Shuffle the trial pages per participant (seeded)"),
    )

    def __init__(self, study: Study, *args, **kwargs) -> None:
        stored = study.design or {}
        initial = kwargs.setdefault("initial", {})
        conditions = study.conditions.order_by("position", "pk")
        items = study.items.order_by("position", "pk")
        initial.setdefault(
            "conditions",
            list(conditions.filter(key__in=stored["conditions"]) if stored else conditions),
        )
        main = items.filter(key__in=stored["items"]) if stored else items.filter(is_practice=False)
        initial.setdefault("items", list(main))
        practice = (
            items.filter(key__in=stored.get("practice_items", ()))
            if stored
            else items.filter(is_practice=True)
        )
        initial.setdefault("practice_items", list(practice))
        if stored:
            initial.setdefault("design", stored["design"])
            initial.setdefault("attention_checks", stored.get("attention_checks", 0))
            initial.setdefault("randomize_order", stored.get("randomize_order", True))
            initial.setdefault(
                "questions", list(study.questions.filter(key__in=stored.get("questions", ())))
            )
        super().__init__(*args, **kwargs)
        self.study = study
        self.fields["conditions"].queryset = conditions
        self.fields["items"].queryset = items
        self.fields["practice_items"].queryset = items
        self.fields["questions"].queryset = study.questions.filter(
            kind__in=builder_question_kinds()
        ).order_by("position", "pk")
        self.fields["questions"].help_text = _questions_help()
        self.fields["items"].label_from_instance = _item_label
        self.fields["practice_items"].label_from_instance = _item_label

    def clean(self):
        cleaned = super().clean()
        if self.errors:
            return cleaned
        practice = {i.key for i in cleaned["practice_items"]}
        both = sorted(practice & {i.key for i in cleaned["items"]})
        if both:
            self.add_error(
                "practice_items",
                gettext("Also a trial item: %(keys)s.") % {"keys": ", ".join(both)},
            )
            return cleaned
        try:
            cleaned["spec"] = DesignSpec(
                design=cleaned["design"],
                conditions=tuple(c.key for c in cleaned["conditions"]),
                items=tuple(i.key for i in cleaned["items"]),
                practice_items=tuple(i.key for i in cleaned["practice_items"]),
                attention_checks=cleaned["attention_checks"],
                seed=(self.study.design or {}).get("seed", self.study.pk or 0),
            )
        except DesignError as error:
            raise forms.ValidationError(str(error)) from None
        return cleaned


def _item_label(item) -> str:
    return item.key if item.text == item.key else f"{item.key}: {item.text}"


class StudyDesignMixin:
    """Add the design builder page to the study admin."""

    def design_urls(self):
        return [
            path(
                "<path:object_id>/design/",
                self.admin_site.admin_view(self.design_view),
                name="studyplatform_study_design",
            ),
            path(
                "<path:object_id>/new-version/",
                self.admin_site.admin_view(self.new_version_view),
                name="studyplatform_study_new_version",
            ),
        ]

    def new_version_view(self, request: HttpRequest, object_id: str) -> HttpResponse:
        """Make a draft copy of the study as its next version (POST), and open it."""
        study = self._get_visible_study(request, object_id)
        if request.method != "POST" or not self.has_add_permission(request):
            return redirect(reverse("admin:studyplatform_study_change", args=[study.pk]))
        copy = do_create_study_version(study, owner=request.user)
        messages.success(
            request,
            gettext(
                "Made “%(copy)s”, a draft: change its design, generate, pilot and open it. "
                "“%(study)s” and its participants stay as they were."
            )
            % {"copy": copy.title, "study": study.title},
        )
        return redirect(reverse("admin:studyplatform_study_change", args=[copy.pk]))

    def design_view(self, request: HttpRequest, object_id: str) -> HttpResponse:
        """Show the design's summary and the builder; build the pages on POST."""
        study = self._get_visible_study(request, object_id)
        can_build = (
            self.has_change_permission(request, study)
            and study.status == "draft"
            and not study.design_locked
        )
        form = DesignForm(study, request.POST if request.method == "POST" else None)
        if request.method == "POST" and can_build and form.is_valid():
            questions = list(form.cleaned_data["questions"])
            try:
                built = do_build_design(
                    study,
                    form.cleaned_data["spec"],
                    questions,
                    form.cleaned_data["randomize_order"],
                )
            except DesignRejected as error:
                form.add_error(None, error.message)
            else:
                created = built.question_created
                if created is not None:
                    messages.info(
                        request,
                        gettext(
                            "Created the question “%(text)s” (%(key)s); "
                            "edit its wording on its page."
                        )
                        % {"text": created.text, "key": created.key},
                    )
                messages.success(
                    request,
                    gettext(
                        "Built %(pages)d pages (%(practice)d practice, "
                        "%(checks)d attention checks)."
                    )
                    % {
                        "pages": built.pages,
                        "practice": built.practice_pages,
                        "checks": built.attention_checks,
                    },
                )
                return redirect(reverse("admin:studyplatform_study_design", args=[study.pk]))
        summary = summarize_design(study)
        return self._page(
            request,
            "design.html",
            gettext("Design of “%(title)s”") % {"title": study.title},
            study=study,
            form=form,
            summary=summary,
            can_build=can_build,
            answer_s=ANSWER_S,
            info_page_s=INFO_PAGE_S,
            mismatched=mismatched_pairs(study),
        )
