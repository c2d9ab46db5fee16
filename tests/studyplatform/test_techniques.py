"""Test that conditions and items are a validated contract in the admin and on import."""

import re

import pytest
from django.core.exceptions import ValidationError
from django.urls import reverse

from studyplatform.actions import StudyImportError, do_import_study
from studyplatform.demo import DEMO_STUDIES
from studyplatform.lib.exchange import export_study
from studyplatform.lib.stimuli import clip_spec
from studyplatform.models import Condition, Item
from synthesis.techniques import MOTION, REGISTRY, Parameter, Technique
from tests.conftest import as_draft

pytestmark = pytest.mark.django_db

TOY = Technique(
    name="toy",
    label="Toy slow motion",
    kinds=frozenset({"word"}),
    parameters=(Parameter("slowdown", "int", 1, "Show every frame this many times.", minimum=1),),
    source="a test",
    stage=MOTION,
)


@pytest.fixture
def alice_client(client, alice):
    client.force_login(alice)
    return client


def _change_url(condition: Condition) -> str:
    return reverse("admin:studyplatform_condition_change", args=[condition.pk])


def _post_data(page_form, **changes) -> dict:
    data = {}
    for name, field in page_form.fields.items():
        value = page_form.initial.get(name, field.initial)
        if name == "parameters":
            value = "{}" if not value else __import__("json").dumps(value)
        if value is None:
            value = ""
        data[name] = value
    data.update(changes)
    return data


def test_the_condition_page_offers_each_technique_parameter(alice_client, fingerspelling):
    condition = fingerspelling.conditions.get(key="constant")
    page = alice_client.get(_change_url(condition))
    assert page.status_code == 200
    html = page.content.decode()
    for title in ("Performance (seed 000 §4.3)", "Timing model (seed 000 §4.2–4.3)", "Filming"):
        assert title in html
    assert "Automated spine motion" not in html  # a study of words only
    form = page.context["adminform"].form
    assert form.fields["technique_timing"].initial == "constant"
    assert form.fields["technique_source"].initial == "simulated"
    assert "Constant (243 ms holds, the last 800 ms, 250 ms transitions)" in html


def test_the_generated_form_stores_what_differs_from_the_defaults(alice_client, fingerspelling):
    as_draft(fingerspelling)
    condition = fingerspelling.conditions.get(key="constant")
    form = alice_client.get(_change_url(condition)).context["adminform"].form
    data = _post_data(form, technique_hold_ms="200", technique_timing="constant")
    data["study"] = fingerspelling.pk
    response = alice_client.post(_change_url(condition), data)
    assert response.status_code == 302, response.context["adminform"].form.errors
    condition.refresh_from_db()
    assert condition.parameters == {"timing": "constant", "source": "simulated", "hold_ms": 200.0}
    assert clip_spec(condition, fingerspelling.items.first()).parameters["hold_ms"] == 200.0


def test_the_form_refuses_a_bad_value_and_an_unknown_key(alice_client, fingerspelling):
    as_draft(fingerspelling)
    condition = fingerspelling.conditions.get(key="constant")
    before = dict(condition.parameters)
    form = alice_client.get(_change_url(condition)).context["adminform"].form
    data = _post_data(form, technique_timing="mocap", technique_source="alphabet")
    data["study"] = fingerspelling.pk
    page = alice_client.post(_change_url(condition), data)
    assert page.status_code == 400 and "timing &#x27;mocap&#x27; plays a performance" in (
        page.content.decode()
    )
    data = _post_data(form, parameters='{"spin": false}')
    data["study"] = fingerspelling.pk
    page = alice_client.post(_change_url(condition), data)
    assert "Unknown parameter &#x27;spin&#x27; for a fingerspelled word" in page.content.decode()
    condition.refresh_from_db()
    assert condition.parameters == before  # nothing saved


def test_a_registered_toy_technique_appears_in_the_admin_form(alice_client, fingerspelling):
    condition = fingerspelling.conditions.get(key="variable")
    with REGISTRY.registered(TOY):
        page = alice_client.get(_change_url(condition))
        assert "Toy slow motion (a test)" in page.content.decode()
        assert "technique_slowdown" in page.context["adminform"].form.fields
    assert (
        "technique_slowdown"
        not in alice_client.get(_change_url(condition)).context["adminform"].form.fields
    )


def test_the_study_page_says_what_each_condition_compares(alice_client, fingerspelling, spine):
    html = alice_client.get(
        reverse("admin:studyplatform_study_change", args=[fingerspelling.pk])
    ).content.decode()
    assert "What it compares" in html
    assert "Timing model: Variable (naïve Bayes holds, pose-distance transitions)" in html
    assert "Performance: a simulated capture" in html


def test_the_inline_json_field_is_checked_on_save(alice_client, fingerspelling):
    as_draft(fingerspelling)
    condition = fingerspelling.conditions.get(key="variable")
    condition.parameters = {"timing": "variable", "spine": False}
    with pytest.raises(ValidationError, match=r"'spine' .* does not apply to a fingerspelled word"):
        condition.full_clean()


@pytest.mark.parametrize(
    ("where", "change", "message"),
    [
        (
            "conditions",
            {"parameters": {"spin": False}},
            r"conditions\[0\]: parameters: Unknown "
            "parameter 'spin'",
        ),
        ("conditions", {"parameters": {"spine": "yes"}}, "spine must be true or false"),
        (
            "conditions",
            {"parameters": {"timing": "constant"}},
            "Condition 'spine-on' cannot render this item",
        ),
        ("items", {"kind": "poem"}, r"items\[0\]: kind: .*poem"),
        ("items", {"parameters": {"seed": -1}}, "seed must be at least 0"),
    ],
)
def test_import_refuses_bad_parameters_naming_them(alice, spine, where, change, message):
    data = export_study(spine)
    data[where][0].update(change)
    with pytest.raises(StudyImportError, match=message):
        do_import_study(data, owner=alice, slug="copy")
    assert not Item.objects.filter(study__slug="copy").exists()


def test_the_demo_definitions_pass_the_contract(alice):
    for build in DEMO_STUDIES:
        study = do_import_study(build(), owner=alice, status="draft").study
        for condition in study.conditions.all():
            condition.full_clean()


def test_an_open_study_in_the_field_is_never_re_rendered_silently(fingerspelling):
    from studyplatform.actions import do_enroll_participant
    from studyplatform.actions.stimuli import GenerateOptions, RerenderRefused, do_generate_stimuli
    from studyplatform.models import Stimulus

    do_generate_stimuli(fingerspelling, GenerateOptions(enqueue=False))
    Stimulus.objects.update(status=Stimulus.Status.READY)
    do_enroll_participant(fingerspelling)
    condition = fingerspelling.conditions.get(key="constant")
    condition.parameters = {**condition.parameters, "hold_ms": 300}
    condition.save()
    before = sorted(Stimulus.objects.values_list("content_hash", "status"))
    with pytest.raises(RerenderRefused, match=r"is open: 9 of its rendered clips would change"):
        do_generate_stimuli(fingerspelling, GenerateOptions(enqueue=False))
    assert sorted(Stimulus.objects.values_list("content_hash", "status")) == before
    do_generate_stimuli(fingerspelling, GenerateOptions(enqueue=False, rerender_open=True))
    after = sorted(Stimulus.objects.values_list("content_hash", "status"))
    # The constant condition's 8 words and the example word, and only they.
    assert len({h for h, _ in before} - {h for h, _ in after}) == 9


def test_the_migration_keeps_the_meaning_of_old_word_conditions(fingerspelling):
    from importlib import import_module

    from django.apps import apps

    migration = import_module("studyplatform.migrations.0005_condition_source")
    fingerspelling.conditions.filter(key="variable").update(parameters={"timing": "variable"})
    fingerspelling.conditions.filter(key="constant").update(parameters={"timing": "simple"})
    migration.spell_out_source(apps, None)
    parameters = dict(fingerspelling.conditions.values_list("key", "parameters"))
    assert parameters["variable"] == {"timing": "variable", "source": "simulated"}
    assert parameters["constant"] == {"timing": "simple"}  # was always the alphabet


def test_the_admin_check_names_a_wrong_type_and_an_unknown_item_kind(fingerspelling):
    as_draft(fingerspelling)
    condition = fingerspelling.conditions.get(key="constant")
    condition.parameters = {"timing": "constant", "hold_ms": "long"}
    with pytest.raises(ValidationError, match="hold_ms must be a number, not 'long'"):
        condition.full_clean()
    item = fingerspelling.items.first()
    item.kind = "poem"
    with pytest.raises(ValidationError) as raised:
        item.full_clean()
    assert "poem" in raised.value.message_dict["kind"][0]
    # A sign pair is a kind the engine renders, but not under the study's timing models.
    item.kind, item.text = "sign_pair", "WHERE SURPRISE"
    with pytest.raises(ValidationError, match="does not apply to a sign pair"):
        item.full_clean()


def test_the_parameters_schema_comes_from_the_registry(alice_client):
    from studyplatform.lib.exchange import parameters_schema

    url = reverse("admin:studyplatform_study_parameters_schema")
    served = alice_client.get(url).json()
    assert served == parameters_schema()
    word = served["$defs"]["word"]["properties"]
    assert word["timing"]["enum"][0] == "mocap" and word["rate_hz"]["x-units"] == "Hz"
    with REGISTRY.registered(TOY):
        assert "slowdown" in parameters_schema()["$defs"]["word"]["properties"]
    assert "Import" in alice_client.get(reverse("admin:studyplatform_study_import")).text


def test_an_item_s_text_is_checked_for_its_kind(spine):
    """A sign pair is two glosses and a word spells letters: refused on save, not at render."""
    as_draft(spine)
    item = spine.items.first()
    item.kind = "sign_pair"
    item.text = "WHERE SURPRISE LOST"
    with pytest.raises(ValidationError, match="A sign pair is two glosses"):
        item.full_clean()
    item.text = "WHERE SURPRISE"
    item.full_clean()


def test_a_locked_conditions_page_shows_each_technique_value(alice_client, fingerspelling):
    """A condition of an open study is shown read-only: each technique field with its
    value in words (Django would show "None" for a field only the form has)."""
    condition = fingerspelling.conditions.get(key="constant")
    page = alice_client.get(_change_url(condition)).content.decode()
    values = {
        label.strip(): value.strip()
        for label, value in re.findall(
            r'<label>([^<]*):</label>\s*<div class="readonly">([^<]*)</div>', page
        )
    }
    timing = next(t for t in REGISTRY.techniques if t.name == "timing").parameters[0]
    assert values["Timing"] == timing.labels["constant"]
    assert values["Hold ms"] == f"{condition.parameters['hold_ms']:g} ms"
    assert "None" not in values.values()
