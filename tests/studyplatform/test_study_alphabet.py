"""Test a study's manual alphabet: its words checked and rendered in it (issue 55, item 2).

References: the Libras manual alphabet has Ç (synthesis/data/alphabets/libras.yaml);
ASL's has A–Z only. A study of uploaded clips renders nothing, so its words are the
researcher's own (a TİD study spells ÇAY).
"""

import pytest
from django.core.exceptions import ValidationError
from django.urls import reverse

from studyplatform.actions import do_import_study
from studyplatform.lib.exchange import export_study
from studyplatform.lib.stimuli import clip_spec
from studyplatform.models import Condition, Item, Study

pytestmark = pytest.mark.django_db


@pytest.fixture
def libras_study(alice):
    study = Study.objects.create(
        owner=alice,
        slug="soletrar",
        title="Soletração",
        language="pt-br",
        sign_language="Libras",
        manual_alphabet="libras",
    )
    Condition.objects.create(
        study=study, key="simple", label="Simple", parameters={"timing": "simple"}
    )
    return study


_KEYS = {"ÇAY": "cay", "DAĞ": "dag"}


def _item(study, text: str, **fields) -> Item:
    item = Item(study=study, key=_KEYS[text], text=text, position=1, **fields)
    item.full_clean()
    item.save()
    return item


def test_a_libras_study_takes_and_renders_words_with_its_letters(libras_study):
    item = _item(libras_study, "ÇAY")
    spec = clip_spec(libras_study.conditions.get(), item)
    assert spec.parameters["alphabet"] == "libras"


def test_a_word_outside_the_study_alphabet_is_refused_naming_it(libras_study):
    Study.objects.filter(pk=libras_study.pk).update(manual_alphabet="asl")
    libras_study.refresh_from_db()
    with pytest.raises(ValidationError) as raised:
        _item(libras_study, "ÇAY")
    assert "'Ç' is not a letter of the ASL manual alphabet (A–Z)" in str(raised.value)
    assert "Condition 'simple'" in str(raised.value)
    # An item may set its own alphabet, as a condition may.
    Item.objects.all().delete()
    _item(libras_study, "ÇAY", parameters={"alphabet": "libras"})


def test_a_study_of_uploaded_clips_takes_any_letters(libras_study):
    Study.objects.filter(pk=libras_study.pk).update(manual_alphabet="asl")
    libras_study.conditions.update(source="uploaded", parameters={})
    libras_study.refresh_from_db()
    _item(libras_study, "ÇAY")
    _item(libras_study, "DAĞ")
    rendered = Condition(study=libras_study, key="rendered", parameters={}, position=2)
    with pytest.raises(ValidationError, match=r"Item 'cay'.*'Ç' is not a letter of the ASL"):
        rendered.full_clean()


def test_the_study_alphabet_cannot_change_under_its_words(libras_study):
    _item(libras_study, "ÇAY")
    libras_study.manual_alphabet = "asl"
    with pytest.raises(ValidationError) as raised:
        libras_study.full_clean()
    assert "manual_alphabet" in raised.value.message_dict
    assert "Item 'cay' under condition 'simple'" in raised.value.message_dict["manual_alphabet"][0]


def test_a_condition_fitted_to_asl_is_refused_in_a_libras_study(libras_study):
    variable = Condition(
        study=libras_study, key="variable", parameters={"timing": "variable"}, position=3
    )
    with pytest.raises(ValidationError, match="Variable model, fitted to ASL"):
        variable.full_clean()


def test_the_alphabet_travels_with_an_exported_study(libras_study, alice):
    _item(libras_study, "ÇAY")
    data = export_study(libras_study)
    assert data["study"]["manual_alphabet"] == "libras"
    copy = do_import_study(data, owner=alice, slug="soletrar-2").study
    assert copy.manual_alphabet == "libras"
    assert copy.items.get().text == "ÇAY"


def test_the_study_page_offers_the_engine_alphabets(client, alice, libras_study):
    client.force_login(alice)
    page = client.get(reverse("admin:studyplatform_study_change", args=[libras_study.pk]))
    html = page.content.decode()
    assert 'name="manual_alphabet"' in html
    assert "Libras (Língua Brasileira de Sinais)" in html
    assert "ASL (American Sign Language)" in html


def test_the_condition_page_shows_the_study_alphabet_as_its_default(client, alice, libras_study):
    _item(libras_study, "ÇAY")
    condition = libras_study.conditions.get()
    url = reverse("admin:studyplatform_condition_change", args=[condition.pk])
    client.force_login(alice)
    form = client.get(url).context["adminform"].form
    assert form.fields["technique_alphabet"].initial == "libras"
    data = {name: form[name].value() for name in form.fields}
    data.update(study=libras_study.pk, parameters="{}", avatar="")
    data = {name: "" if value is None else value for name, value in data.items()}
    assert client.post(url, data).status_code == 302
    condition.refresh_from_db()
    assert "alphabet" not in condition.parameters  # the study's, not stored
    data["technique_alphabet"] = "asl"
    page = client.post(url, data)
    assert "&#x27;Ç&#x27; is not a letter of the ASL manual alphabet" in page.content.decode()
