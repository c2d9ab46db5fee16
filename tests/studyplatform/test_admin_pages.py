"""Test that every admin page a researcher uses renders, and the study tools work."""

import json

import pytest
from django.core.files.uploadedfile import SimpleUploadedFile
from django.urls import reverse

from studyplatform.actions import Answer, do_enroll_participant, do_save_response
from studyplatform.lib.exchange import export_study
from studyplatform.models import Study
from tests.conftest import as_draft

pytestmark = pytest.mark.django_db

MODELS = (
    "study",
    "question",
    "block",
    "trial",
    "stimulus",
    "participant",
    "personalanswer",
    "response",
    "mediaevent",
)


@pytest.fixture
def alice_client(client, alice):
    client.force_login(alice)
    return client


@pytest.fixture
def with_data(fingerspelling):
    participant = do_enroll_participant(fingerspelling)
    trial = fingerspelling.trials.get(key="cmp-01")
    do_save_response(participant, trial, trial.questions.get(), Answer(choice_position=1))
    return participant


@pytest.mark.parametrize("model", MODELS)
def test_changelists_render(alice_client, with_data, model):
    assert alice_client.get(reverse(f"admin:studyplatform_{model}_changelist")).status_code == 200


def test_admin_index_lists_the_researchers_sections(alice_client):
    page = alice_client.get(reverse("admin:index"))
    assert page.status_code == 200
    assert "Studies" in page.text and "Trials" in page.text and "Responses" in page.text


def test_change_pages_render(alice_client, with_data, fingerspelling):
    objects = {
        "study": fingerspelling,
        "trial": fingerspelling.trials.get(key="cmp-01"),
        "question": fingerspelling.questions.get(key="age"),
        "block": fingerspelling.blocks.get(key="comparisons"),
        "answeroption": fingerspelling.questions.get(key="age").options.first(),
        "participant": with_data,
        "response": with_data.responses.get(),
    }
    for model, obj in objects.items():
        page = alice_client.get(reverse(f"admin:studyplatform_{model}_change", args=[obj.pk]))
        assert page.status_code == 200, model


@pytest.mark.parametrize("model", ["study", "question", "block", "trial"])
def test_add_pages_render(alice_client, fingerspelling, model):
    assert alice_client.get(reverse(f"admin:studyplatform_{model}_add")).status_code == 200


def test_collected_data_cannot_be_edited(alice_client, with_data):
    url = reverse("admin:studyplatform_response_change", args=[with_data.responses.get().pk])
    page = alice_client.get(url)
    assert 'name="_save"' not in page.text
    assert alice_client.get(reverse("admin:studyplatform_response_add")).status_code == 403


def test_study_page_links_preview_and_export(alice_client, fingerspelling):
    page = alice_client.get(reverse("admin:studyplatform_study_change", args=[fingerspelling.pk]))
    assert reverse("admin:studyplatform_study_preview", args=[fingerspelling.pk]) in page.text
    assert reverse("admin:studyplatform_study_export", args=[fingerspelling.pk]) in page.text
    assert reverse("study_welcome", args=[fingerspelling.slug]) in page.text  # to send out


def test_preview_shows_every_page_in_order(alice_client, fingerspelling):
    page = alice_client.get(reverse("admin:studyplatform_study_preview", args=[fingerspelling.pk]))
    assert page.status_code == 200
    # consent + demographics + instructions + practice + 48 comparisons + attention
    # check + closing + thank-you
    assert page.text.count('class="preview-page"') == 55
    # Numbered as participants see them: consent and thank-you are not counted.
    assert "Page 53 of 53" in page.text and "Page 54" not in page.text
    assert "Which animation is the most similar to actual fingerspelling" in page.text
    assert "Clip not ready yet" in page.text
    assert "simulated" in page.text


def test_preview_shows_the_participant_widgets_in_the_study_language(alice_client, fingerspelling):
    """The researcher's page stays English; the questions read as participants see them."""
    Study.objects.filter(pk=fingerspelling.pk).update(language="tr")
    page = alice_client.get(reverse("admin:studyplatform_study_preview", args=[fingerspelling.pk]))
    assert 'class="preview-questions" lang="tr"' in page.text
    assert "E-posta adresiniz" in page.text  # the e-mail question's "Your e-mail address"
    assert "Every page in design order" in page.text
    assert 'lang="en"' in page.text.split("<body", 1)[0]


def test_export_downloads_the_definition(alice_client, fingerspelling):
    url = reverse("admin:studyplatform_study_export", args=[fingerspelling.pk])
    download = alice_client.get(url)
    assert download["Content-Disposition"] == (
        'attachment; filename="fingerspelling-timing.study.json"'
    )
    assert json.loads(download.content) == json.loads(json.dumps(export_study(fingerspelling)))


def test_import_through_the_admin(alice_client, fingerspelling):
    upload = SimpleUploadedFile(
        "study.json", json.dumps(export_study(fingerspelling)).encode(), "application/json"
    )
    response = alice_client.post(
        reverse("admin:studyplatform_study_import"), {"definition": upload, "slug": "rerun"}
    )
    study = Study.objects.get(slug="rerun")
    assert response.status_code == 302
    assert response["Location"] == reverse("admin:studyplatform_study_change", args=[study.pk])
    assert study.trials.count() == fingerspelling.trials.count()
    # Issue 35: it came "closed" and locked with 0 participants, under the same title.
    assert study.status == Study.Status.DRAFT and not study.design_locked
    assert study.title == f"{fingerspelling.title} (imported)"


@pytest.mark.parametrize(
    "content, message",
    [
        (
            b"{not json",
            "The file is not valid JSON: Expecting property name enclosed in double quotes "
            "at line 1, column 2.",
        ),
        (b"\xff\xfe", "The file is not UTF-8 text."),
        (b"[" * 100_000 + b"]" * 100_000, "The file is JSON nested deeper than 32 levels."),
        (b'{"format": NaN}', "The file is JSON with NaN, which JSON does not allow."),
        (
            b'{"format": "signstudy.study", "version": 1, "study": {"slug": "x"}}',
            "Not imported: study: title: This field cannot be blank.",
        ),
    ],
)
def test_import_of_a_bad_file_says_why(alice_client, content, message):
    before = Study.objects.count()
    page = alice_client.post(
        reverse("admin:studyplatform_study_import"),
        {"definition": SimpleUploadedFile("s.json", content)},
    )
    assert page.status_code == 400  # refused, and the form says why
    assert message in page.text
    assert Study.objects.count() == before


def test_duplicate_action(alice_client, fingerspelling):
    alice_client.post(
        reverse("admin:studyplatform_study_changelist"),
        {"action": "duplicate_studies", "_selected_action": [fingerspelling.pk]},
    )
    copy = Study.objects.get(slug="fingerspelling-timing-copy")
    assert copy.status == "draft"
    assert copy.trials.count() == 53


def test_export_of_several_studies_is_a_zip(admin_client, fingerspelling, spine):
    import io
    import zipfile

    response = admin_client.post(
        reverse("admin:studyplatform_study_changelist"),
        {"action": "export_studies", "_selected_action": [fingerspelling.pk, spine.pk]},
    )
    names = zipfile.ZipFile(io.BytesIO(response.content)).namelist()
    assert sorted(names) == ["fingerspelling-timing.study.json", "spine-motion.study.json"]


def test_trial_form_rejects_questions_of_the_wrong_kind(alice_client, fingerspelling):
    as_draft(fingerspelling)
    trial = fingerspelling.trials.get(key="cmp-01")
    age = fingerspelling.questions.get(key="age")
    page = alice_client.post(
        reverse("admin:studyplatform_trial_change", args=[trial.pk]),
        {
            "study": fingerspelling.pk,
            "block": trial.block_id,
            "key": trial.key,
            "kind": "pairwise",
            "item": trial.item_id,
            "condition_a": trial.condition_a_id,
            "condition_b": trial.condition_b_id,
            "questions": [age.pk],
            "position": 0,
            "studyplatform-aslvideo-content_type-object_id-TOTAL_FORMS": 0,
            "studyplatform-aslvideo-content_type-object_id-INITIAL_FORMS": 0,
        },
    )
    assert page.status_code == 400  # the form again, with its errors
    assert "A pairwise forced choice trial cannot ask age." in page.text
    assert list(trial.questions.values_list("key", flat=True)) == ["most-natural"]


def test_new_inline_rows_come_after_the_others_unless_a_position_is_typed(spine):
    """Issue 35, point 9: every new inline row got position 0; a position can be negative."""
    from django.forms.models import inlineformset_factory

    from studyplatform.admin.design import AnswerOptionInline
    from studyplatform.admin.positions import PositionedFormSet
    from studyplatform.admin.studies import BlockInline, ConditionInline, ItemInline, TrialInline
    from studyplatform.models import AnswerOption, Question

    for inline in (AnswerOptionInline, BlockInline, ConditionInline, ItemInline, TrialInline):
        assert issubclass(inline.formset, PositionedFormSet), inline
    as_draft(spine)
    question = spine.questions.get(key="preferred-language")
    existing = list(question.options.order_by("position"))
    formset_class = inlineformset_factory(
        Question, AnswerOption, formset=PositionedFormSet, fields=("position", "value", "label")
    )
    data = {
        "options-TOTAL_FORMS": str(len(existing) + 3),
        "options-INITIAL_FORMS": str(len(existing)),
    }
    for index, option in enumerate(existing):
        data |= {
            f"options-{index}-id": str(option.pk),
            f"options-{index}-position": str(option.position),
            f"options-{index}-value": str(option.value),
            f"options-{index}-label": option.label,
        }
    new = [("0", "7", "Added first"), ("0", "8", "Added second"), ("-1", "9", "Put first")]
    for index, (position, value, label) in enumerate(new, len(existing)):
        data |= {
            f"options-{index}-position": position,
            f"options-{index}-value": value,
            f"options-{index}-label": label,
        }
    formset = formset_class(data, instance=question)
    assert formset.is_valid(), formset.errors
    formset.save()
    last = max(option.position for option in existing)
    positions = dict(question.options.values_list("label", "position"))
    assert positions["Added first"] == last + 1 and positions["Added second"] == last + 2
    assert positions["Put first"] == -1
    assert question.options.order_by("position").first().label == "Put first"


def test_every_field_a_definition_exports_is_edited_in_the_admin_or_said_why(alice, rf):
    """Issue 57: the admin's field lists repeated exchange.py's with nothing tying them;
    a field added to a model and its export but not to the admin went unnoticed. Each
    model's admin form (or the inline that edits it) shows every exported field, or
    NOT_EDITED_HERE says why not."""
    from django.apps import apps
    from django.contrib import admin

    from studyplatform.admin import NOT_EDITED_HERE
    from studyplatform.lib.exchange import EXPORTED

    request = rf.get("/admin/")
    request.user = alice
    inlines = {
        inline.model: inline(model, admin.site)
        for model, model_admin in admin.site._registry.items()
        for inline in model_admin.inlines
    }
    checked = []
    for name, exported in EXPORTED.items():
        model = apps.get_model("studyplatform", name)
        editor = admin.site._registry.get(model) or inlines.get(model)
        if editor is None:
            continue  # Recording, UploadedClip: files, added on their own pages
        shown = set()
        for _, options in editor.get_fieldsets(request, None):
            for field in options["fields"]:
                shown.update(field if isinstance(field, tuple | list) else [field])
        missing = set(exported) - shown - set(NOT_EDITED_HERE.get(name, {}))
        assert not missing, f"{name}: {sorted(missing)} exported but not in the admin"
        assert set(NOT_EDITED_HERE.get(name, {})) <= set(exported) - shown, name
        checked.append(name)
    assert len(checked) == 8, checked


@pytest.mark.parametrize(
    ("kind", "points"),
    [
        (
            "likert",
            [(1, "Not at all"), (2, "Slightly"), (3, "Moderately"), (4, "Very"), (5, "Extremely")],
        ),
        ("slider", [(0, "Not at all"), (100, "Completely")]),
        ("open", []),
    ],
)
def test_a_new_rating_question_starts_with_labelled_points(client, spine, kind, points):
    """Issue 55, item 7: a Likert question added in the admin had no scale points (all
    five typed by hand); it starts with its kind's labelled points, which the researcher
    rewords. Points typed in the same form are kept as they are."""
    from studyplatform.models import Question

    as_draft(spine)
    client.force_login(spine.owner)
    management = {
        "options-TOTAL_FORMS": 0,
        "options-INITIAL_FORMS": 0,
        "studyplatform-aslvideo-content_type-object_id-TOTAL_FORMS": 0,
        "studyplatform-aslvideo-content_type-object_id-INITIAL_FORMS": 0,
    }
    fields = {"study": spine.pk, "position": 0, "kind": kind, "text": "How clear?"}
    added = client.post(
        reverse("admin:studyplatform_question_add"), {**fields, "key": "clear", **management}
    )
    assert added.status_code == 302, added.content[:2000]
    question = Question.objects.get(study=spine, key="clear")
    assert list(question.options.values_list("value", "label")) == points
    typed = {**management, "options-TOTAL_FORMS": 1, "options-0-position": 1}
    typed |= {"options-0-value": 3, "options-0-label": "Mine"}
    client.post(reverse("admin:studyplatform_question_add"), {**fields, "key": "own", **typed})
    own = Question.objects.get(study=spine, key="own")
    assert list(own.options.values_list("value", "label")) == [(3, "Mine")]
