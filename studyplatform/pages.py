"""Lay out one page of a participant's schedule: its clips, questions, answers and ASL.

Read-only: the views render what :func:`participant_page` returns. The queries are few
and fixed per page (no query per question or option), so a page stays fast with many
participants at once.
"""

from dataclasses import dataclass, field

from django.urls import reverse

from studyplatform.asl import asl_videos, with_templates
from studyplatform.lib.participants import page_count
from studyplatform.lib.presentation import presented_conditions
from studyplatform.models import (
    AnswerOption,
    Block,
    Participant,
    PersonalAnswer,
    Question,
    Response,
    Stimulus,
    Study,
    Trial,
)
from studyplatform.questions import question_type


@dataclass(frozen=True)
class PageClip:
    """One clip on a page: its number (1 or 2), label and rendered files, if any."""

    number: int
    label: str
    video_url: str = ""
    poster_url: str = ""
    width: int = 640
    height: int = 480


@dataclass(frozen=True)
class PageQuestion:
    """A question with its options and the participant's current answer (or None)."""

    question: Question
    options: tuple[AnswerOption, ...]
    answer: str = ""
    video_url: str = ""  # a signed answer already given


@dataclass(frozen=True)
class ParticipantPage:
    """Everything one page shows a participant, and where it sits in their schedule."""

    number: int
    total: int
    trial: Trial
    block: Block
    block_intro: bool
    clips: tuple[PageClip, ...] = ()
    questions: tuple[PageQuestion, ...] = ()
    asl: dict = field(default_factory=dict)

    @property
    def has_signed_text(self) -> bool:
        """Return whether some text on the page has an ASL version (the buttons aside)."""
        return any(key[0] != "ui" for key in self.asl)

    @property
    def percent(self) -> int:
        """Return the share of pages done before this one, in percent."""
        return round(100 * (self.number - 1) / self.total) if self.total else 100

    @property
    def is_last(self) -> bool:
        return self.number == self.total


def _answer_text(response: Response | None, question: Question) -> str:
    """Return the stored answer as the value the page's control holds."""
    return "" if response is None else question_type(question).display(question, response)


def participant_page(participant: Participant, number: int, trial: Trial) -> ParticipantPage:
    """Return page *number* of the participant's schedule, whose trial is *trial*.

    *trial* comes with its block, item, conditions and questions with their options
    (as :func:`~studyplatform.actions.page_trial` returns it).
    """
    study = participant.study
    previous = participant.schedule[number - 2].get("trial") if number > 1 else None
    block_intro = bool(trial.block.intro_text) and (
        previous is None
        or not Trial.objects.filter(study=study, key=previous, block=trial.block)
        .order_by()
        .exists()
    )
    questions = sorted(trial.questions.all(), key=lambda q: (q.position, q.pk))
    clips = []
    if trial.item_id and trial.condition_a_id:
        shown = presented_conditions(participant, trial)
        conditions = [c for c in shown if c is not None]
        stimuli = {
            s.condition_id: s
            for s in Stimulus.objects.filter(
                item_id=trial.item_id, condition__in=conditions, status=Stimulus.Status.READY
            ).order_by()
        }
        two = len(conditions) == 2
        for position, condition in enumerate(conditions, 1):
            stimulus = stimuli.get(condition.pk)
            label = f"Clip {position}" if two else ("Clip" if questions else "Example clip")
            clips.append(
                PageClip(
                    number=position,
                    label=label,
                    video_url=stimulus.video.url if stimulus and stimulus.video else "",
                    poster_url=stimulus.poster.url if stimulus and stimulus.poster else "",
                    width=(stimulus.width if stimulus and stimulus.width else 640),
                    height=(stimulus.height if stimulus and stimulus.height else 480),
                )
            )
    responses = {
        r.question_id: r
        for r in Response.objects.filter(participant=participant, trial=trial).order_by()
    }
    personal_questions = [q for q in questions if q.is_personal]
    personal = {}
    if personal_questions:  # most pages ask none: no query
        personal = dict(
            PersonalAnswer.objects.filter(
                participant=participant, question__in=personal_questions
            ).values_list("question_id", "value")
        )
    page_questions = []
    for question in questions:
        answer = (
            personal.get(question.pk, "")
            if question.is_personal
            else _answer_text(responses.get(question.pk), question)
        )
        options = tuple(sorted(question.options.all(), key=lambda o: (o.position, o.value)))
        response = responses.get(question.pk)
        video_url = (
            reverse("participant_answer_video", args=[participant.token, response.pk])
            if response is not None and response.video
            else ""
        )
        page_questions.append(PageQuestion(question, options, answer, video_url))
    asl: dict = {}
    if participant.language == Participant.Language.ASL_ENGLISH:
        objects = [trial, trial.block, *questions]
        objects += [option for q in page_questions for option in q.options]
        asl = with_templates(asl_videos(objects), participant.study, objects, ui=True)
    return ParticipantPage(
        number=number,
        total=page_count(participant),
        trial=trial,
        block=trial.block,
        block_intro=block_intro,
        clips=tuple(clips),
        questions=tuple(page_questions),
        asl=asl,
    )


def study_asl(study: Study, language: str) -> dict:
    """Return the study's own ASL videos (welcome, consent, thank-you) for *language*."""
    if language != Participant.Language.ASL_ENGLISH:
        return {}
    return with_templates(asl_videos([study]), study, [study])
