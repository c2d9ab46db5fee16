"""Test the model-level rules researchers meet when editing a design."""

import pytest
from django.core.exceptions import ValidationError
from django.db import IntegrityError, transaction

from studyplatform.models import Question, Trial
from tests.conftest import as_draft

pytestmark = pytest.mark.django_db


@pytest.fixture(autouse=True)
def _editable_demos(request):
    """These tests validate design objects of the demo studies, which only a draft allows."""
    as_draft(
        *(
            request.getfixturevalue(n)
            for n in ("fingerspelling", "spine")
            if n in request.fixturenames
        )
    )


def test_comparison_needs_two_clips(fingerspelling):
    trial = fingerspelling.trials.get(key="cmp-01")
    trial.condition_b = None
    with pytest.raises(ValidationError, match="A comparison needs an item and two conditions"):
        trial.full_clean()


def test_identical_clips_only_in_attention_checks(fingerspelling):
    trial = fingerspelling.trials.get(key="cmp-01")
    trial.condition_b = trial.condition_a
    with pytest.raises(ValidationError, match="only allowed in attention checks"):
        trial.full_clean()
    trial.is_attention_check = True
    trial.expected_answer = "none"
    trial.full_clean()


def test_clips_from_another_study_are_rejected(fingerspelling, spine):
    trial = fingerspelling.trials.get(key="cmp-01")
    trial.condition_a = spine.conditions.first()
    with pytest.raises(ValidationError, match="This belongs to another study"):
        trial.full_clean()


def test_second_clip_is_refused_by_the_database_outside_comparisons(fingerspelling):
    trial = fingerspelling.trials.get(key="cmp-01")
    with pytest.raises(IntegrityError), transaction.atomic():
        Trial.objects.filter(pk=trial.pk).update(kind="rating")


def test_rating_trial_needs_its_clip(spine):
    trial = spine.trials.get(key="rate-s1")
    trial.item = None
    with pytest.raises(ValidationError, match="needs an item and the condition of its clip"):
        trial.full_clean()


def test_trial_questions_must_suit_the_trial(spine):
    trial = spine.trials.get(key="rate-s1")
    trial.check_questions(trial.questions.all())
    with pytest.raises(ValidationError, match="cannot ask preferred"):
        trial.check_questions([spine.questions.get(key="preferred")])
    with pytest.raises(ValidationError, match="asks no question"):
        trial.check_questions([])


@pytest.mark.parametrize(
    "changes, field",
    [
        ({"kind": "likert", "allow_no_difference": True}, "allow_no_difference"),
        ({"kind": "likert", "allow_signed_answer": True}, "allow_signed_answer"),
        ({"kind": "open", "is_personal": True}, "is_personal"),
        ({"kind": "number", "min_value": 5, "max_value": 1}, "max_value"),
    ],
)
def test_question_settings_must_fit_its_kind(spine, changes, field):
    question = Question(study=spine, key="q", text="?", **changes)
    with pytest.raises(ValidationError) as error:
        question.full_clean()
    assert field in error.value.message_dict


def test_keys_are_unique_within_a_study(spine):
    with pytest.raises(IntegrityError), transaction.atomic():
        Question.objects.create(study=spine, key="clarity", kind="likert", text="again")
