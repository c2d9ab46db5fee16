"""Test saving answers: validation of tampered answers, idempotency, concurrent saves."""

import threading

import pytest
from django.db import close_old_connections, connection

from studyplatform.actions import Answer, AnswerRejected, do_enroll_participant, do_save_response
from studyplatform.models import PersonalAnswer, Response


@pytest.fixture
def participant(fingerspelling):
    """A participant whose clips all show in design order (no swaps)."""
    participant = do_enroll_participant(fingerspelling, recruitment_params={"PROLIFIC_PID": "p1"})
    participant.schedule = [{**entry, "swap": False} for entry in participant.schedule]
    participant.save()
    return participant


def _pairwise_trial(study, key="cmp-01"):
    trial = study.trials.get(key=key)
    return trial, trial.questions.get()


@pytest.mark.django_db
class TestValidation:
    def test_choice_of_clip_stores_condition_and_position(self, participant):
        trial, question = _pairwise_trial(participant.study)
        response = do_save_response(
            participant, trial, question, Answer(choice_position=2, rt_ms=900)
        )
        assert (response.chosen, response.chosen_position, response.rt_ms) == (
            trial.condition_b.key,
            2,
            900,
        )

    def test_swapped_schedule_maps_positions_to_conditions(self, participant):
        trial, question = _pairwise_trial(participant.study)
        participant.schedule = [{"trial": trial.key, "swap": True}]
        response = do_save_response(participant, trial, question, Answer(choice_position=1))
        assert response.chosen == trial.condition_b.key

    @pytest.mark.parametrize("position", [None, 3, -1, 0])
    def test_choice_not_on_the_page_is_rejected(self, participant, position):
        trial, question = _pairwise_trial(participant.study)
        with pytest.raises(AnswerRejected, match="is not one of the clips on this page"):
            do_save_response(participant, trial, question, Answer(choice_position=position))
        assert not Response.objects.exists()

    def test_no_difference_only_when_the_question_offers_it(self, participant):
        trial, question = _pairwise_trial(participant.study)
        question.allow_no_difference = True
        question.save()
        response = do_save_response(participant, trial, question, Answer(choice_position=0))
        assert (response.chosen, response.chosen_position) == ("none", None)

    def test_out_of_range_rating_is_rejected(self, spine):
        participant = do_enroll_participant(spine)
        trial = spine.trials.get(key="rate-s1")
        question = trial.questions.get(key="clarity")
        with pytest.raises(AnswerRejected, match="“6” is not a point of the scale of “clarity”"):
            do_save_response(participant, trial, question, Answer(rating=6))
        assert do_save_response(participant, trial, question, Answer(rating=5)).rating == 5

    def test_number_outside_range_is_rejected(self, spine):
        participant = do_enroll_participant(spine)
        trial = spine.trials.get(key="pretest")
        question = trial.questions.get(key="years-asl")
        with pytest.raises(AnswerRejected, match="outside the allowed range 0 to 100"):
            do_save_response(participant, trial, question, Answer(number=130))

    def test_question_of_another_trial_is_rejected(self, participant):
        trial, _ = _pairwise_trial(participant.study)
        age = participant.study.questions.get(key="age")
        with pytest.raises(AnswerRejected, match="“age” is not asked on this page"):
            do_save_response(participant, trial, age, Answer(rating=1))

    def test_trial_of_another_study_is_rejected(self, participant, spine):
        trial = spine.trials.get(key="prefer-s1")
        with pytest.raises(AnswerRejected, match="not part of your study"):
            do_save_response(participant, trial, trial.questions.get(), Answer(choice_position=1))

    def test_finished_participant_cannot_change_answers(self, participant):
        from django.utils import timezone

        participant.finished_at = timezone.now()
        trial, question = _pairwise_trial(participant.study)
        with pytest.raises(AnswerRejected, match="finished"):
            do_save_response(participant, trial, question, Answer(choice_position=1))

    def test_personal_answers_are_kept_apart(self, participant):
        trial = participant.study.trials.get(key="demographics")
        email = trial.questions.get(key="email")
        do_save_response(participant, trial, email, Answer(text="  a@example.org "))
        assert PersonalAnswer.objects.get().value == "a@example.org"
        assert not Response.objects.exists()


@pytest.mark.django_db
class TestIdempotency:
    def test_same_answer_twice_leaves_one_unchanged_row(self, participant):
        trial, question = _pairwise_trial(participant.study)
        first = do_save_response(participant, trial, question, Answer(choice_position=1, rt_ms=800))
        again = do_save_response(participant, trial, question, Answer(choice_position=1, rt_ms=950))
        assert Response.objects.count() == 1
        assert again.pk == first.pk
        assert (again.revision, again.rt_ms) == (1, 800)

    def test_changed_answer_replaces_and_counts_a_revision(self, participant):
        trial, question = _pairwise_trial(participant.study)
        do_save_response(participant, trial, question, Answer(choice_position=1))
        changed = do_save_response(participant, trial, question, Answer(choice_position=2))
        assert Response.objects.count() == 1
        assert (changed.chosen_position, changed.revision) == (2, 2)


def _save_concurrently(participant_id, trial_id, question_id, answers):
    """Save *answers* at once from as many threads, each with its own connection."""
    from studyplatform.models import Participant, Question, Trial

    barrier = threading.Barrier(len(answers))
    errors = []

    def save(answer):
        try:
            participant = Participant.objects.get(pk=participant_id)
            trial = Trial.objects.get(pk=trial_id)
            question = Question.objects.get(pk=question_id)
            barrier.wait(timeout=10)
            do_save_response(participant, trial, question, answer)
        except Exception as error:  # collected and asserted on below
            errors.append(error)
        finally:
            close_old_connections()
            connection.close()

    threads = [threading.Thread(target=save, args=(answer,)) for answer in answers]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join(timeout=60)
    return errors


@pytest.mark.django_db(transaction=True)
@pytest.mark.parametrize("same_answer", [True, False], ids=["same-answer", "different-answers"])
def test_concurrent_saves_leave_exactly_one_row(fingerspelling, same_answer):
    participant = do_enroll_participant(fingerspelling)
    trial, question = _pairwise_trial(fingerspelling)
    answers = [Answer(choice_position=1 if same_answer else 1 + i % 2) for i in range(8)]
    errors = _save_concurrently(participant.pk, trial.pk, question.pk, answers)
    assert errors == []
    rows = list(Response.objects.filter(participant=participant, trial=trial, question=question))
    assert len(rows) == 1
    if same_answer:
        assert rows[0].revision == 1
    else:
        assert 1 <= rows[0].revision <= 8
        assert rows[0].chosen_position in (1, 2)


@pytest.mark.django_db
def test_database_refuses_a_duplicate_response_outright(participant):
    from django.db import IntegrityError, transaction

    trial, question = _pairwise_trial(participant.study)
    Response.objects.create(participant=participant, trial=trial, question=question, chosen="x")
    with pytest.raises(IntegrityError), transaction.atomic():
        Response.objects.create(participant=participant, trial=trial, question=question, chosen="y")


@pytest.mark.django_db(transaction=True)
def test_concurrent_enrollments_take_distinct_latin_square_rows(fingerspelling):
    """Eight participants enrolling at once get each row of the 4-row square twice."""
    from collections import Counter

    fingerspelling.rotate_conditions = True
    fingerspelling.save()
    barrier, errors, schedules = threading.Barrier(8), [], []

    def enroll():
        try:
            study = type(fingerspelling).objects.get(pk=fingerspelling.pk)
            barrier.wait(timeout=10)
            schedules.append(do_enroll_participant(study).schedule)
        except Exception as error:  # collected and asserted on below
            errors.append(error)
        finally:
            close_old_connections()
            connection.close()

    threads = [threading.Thread(target=enroll) for _ in range(8)]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join(timeout=60)
    assert errors == []
    first = fingerspelling.trials.get(key="cmp-01")
    # A row relabels the first trial's condition A as one condition: the rows taken.
    rows = Counter(
        next(e["a"] for e in schedule if e["trial"] == first.key) for schedule in schedules
    )
    assert len(rows) == 4 and set(rows.values()) == {2}
