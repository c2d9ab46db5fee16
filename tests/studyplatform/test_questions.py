"""Test the question types: one per kind, used by saving, showing, exporting and previewing."""

import csv
import io

import pytest
from django.urls import reverse

from studyplatform.actions import Answer, AnswerRejected, do_enroll_participant, do_save_response
from studyplatform.export import tidy_csv
from studyplatform.models import AnswerOption, Block, Question, Trial, trial_question_kinds
from studyplatform.questions import QUESTION_TYPES, question_type
from tests.conftest import as_draft

pytestmark = pytest.mark.django_db


def test_every_question_kind_has_a_type_with_a_template():
    from django.template.loader import get_template

    assert set(QUESTION_TYPES) == set(Question.Kind.values)
    for kind, type_ in QUESTION_TYPES.items():
        assert type_.kind == kind
        get_template(type_.template)  # exists and compiles
    with pytest.raises(ValueError, match="Unknown question kind 'poll'"):
        question_type("poll")


def test_trial_kinds_ask_the_question_kinds_their_types_name():
    kinds = trial_question_kinds()
    assert kinds["info"] == frozenset()
    assert kinds["pairwise"] == {"pairwise"}
    assert kinds["rating"] == {"likert"}
    assert kinds["demographic"] == {"choice", "number", "short_text", "email"}


@pytest.mark.parametrize(
    ("kind", "value", "expected"),
    [
        ("pairwise", "2", Answer(choice_position=2)),
        ("likert", "4", Answer(rating=4)),
        ("number", "3.5", Answer(number=3.5)),
        ("open", "some words", Answer(text="some words")),
    ],
)
def test_a_type_parses_what_its_widget_posts(kind, value, expected):
    assert question_type(kind).parse(Question(kind=kind), value) == expected


@pytest.mark.parametrize(
    ("kind", "value"), [("pairwise", "x"), ("likert", "1.5"), ("number", "nan"), ("number", "inf")]
)
def test_a_type_refuses_a_post_that_is_not_an_answer(kind, value):
    with pytest.raises(ValueError):
        question_type(kind).parse(Question(kind=kind), value)


def test_settings_that_do_not_apply_to_the_kind_are_named(fingerspelling):
    as_draft(fingerspelling)
    question = Question(
        study=fingerspelling,
        key="q",
        kind="likert",
        text="?",
        allow_no_difference=True,
        is_personal=True,
    )
    with pytest.raises(Exception) as raised:
        question.full_clean()
    assert set(raised.value.message_dict) == {"allow_no_difference", "is_personal"}


def test_a_demographic_question_on_any_page_is_exported(spine):
    closing = Block.objects.create(study=spine, key="end", kind=Block.Kind.CLOSING, position=99)
    device = Question.objects.create(study=spine, key="device", kind="choice", text="Device?")
    AnswerOption.objects.create(question=device, value=1, label="Phone", position=1)
    AnswerOption.objects.create(question=device, value=2, label="Laptop", position=2)
    trial = Trial.objects.create(study=spine, block=closing, key="last", kind="demographic")
    trial.questions.set([device])
    participant = do_enroll_participant(spine)
    preferred = spine.trials.get(key="prefer-s1")
    do_save_response(participant, preferred, preferred.questions.get(), Answer(choice_position=1))
    do_save_response(participant, trial, device, Answer(rating=2))
    with pytest.raises(AnswerRejected, match="not a point of the scale"):
        do_save_response(participant, trial, device, Answer(rating=3))
    rows = list(csv.DictReader(io.StringIO(tidy_csv(spine))))
    # "device" is also a quality column (the browser's device): the answer's column is
    # renamed rather than overwriting it.
    assert rows and {row["demo_device"] for row in rows} == {"Laptop"}
    assert "device" in rows[0]


def test_the_preview_shows_the_participants_own_widgets(client, alice, fingerspelling):
    client.force_login(alice)
    html = client.get(
        reverse("admin:studyplatform_study_preview", args=[fingerspelling.pk])
    ).content.decode()
    # The participant page's fieldset, legend and scale markup, disabled.
    assert '<fieldset class="preview-questions" disabled>' in html
    assert 'class="question" data-question="most-natural"' in html
    assert 'name="q-most-natural"' in html and 'name="q-age"' in html
    assert 'class="question scale" data-question="compare-clips"' in html


def test_a_formula_answer_is_exported_as_text_and_read_back_unchanged(spine):
    """OWASP CSV injection (issue 19): a text answer a spreadsheet would run is escaped
    with an apostrophe, which the analysis reader takes off again."""
    from analysis import read_responses

    comments = spine.trials.get(key="comments")
    question = comments.questions.get()
    answers = ['=HYPERLINK("http://example.org","click")', "'quoted", "+1 (555) 0100", "-2"]
    for text in answers:
        do_save_response(do_enroll_participant(spine), comments, question, Answer(text=text))
    exported = tidy_csv(spine)
    cells = [row["text"] for row in csv.DictReader(io.StringIO(exported)) if row["text"]]
    assert sorted(cells) == sorted(
        ['\'=HYPERLINK("http://example.org","click")', "''quoted", "'+1 (555) 0100", "-2"]
    )
    table = read_responses(io.StringIO(exported))
    assert sorted(table.loc[table["text"].ne(""), "text"]) == sorted(answers)


def test_an_email_question_takes_only_an_email_address(fingerspelling):
    from studyplatform.actions import Answer, AnswerRejected, do_enroll_participant
    from studyplatform.actions import do_save_response as save
    from studyplatform.models import PersonalAnswer

    participant = do_enroll_participant(fingerspelling)
    trial = fingerspelling.trials.get(key="demographics")
    email = trial.questions.get(key="email")
    assert email.kind == "email" and email.is_personal
    with pytest.raises(AnswerRejected, match="“not-an-email” is not an e-mail address"):
        save(participant, trial, email, Answer(text="not-an-email"))
    save(participant, trial, email, Answer(text="me@example.org"))
    assert PersonalAnswer.objects.get(participant=participant).value == "me@example.org"
