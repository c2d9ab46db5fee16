"""Lay out one page of a participant's schedule: its clips, questions, answers and ASL.

Read-only: the views render what :func:`participant_page` returns. The queries are few
and fixed per page (no query per question or option), so a page stays fast with many
participants at once.
"""

from dataclasses import dataclass, field

from django.urls import reverse
from django.utils.translation import gettext as _

from studyplatform.lib.asl import asl_videos, with_templates
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

    @property
    def aspect(self) -> str:
        """Return width / height as a CSS number (the page caps the clip's height with it)."""
        return f"{self.width / self.height:.4f}"


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
    questions = sorted(trial.questions.all(), key=lambda q: (q.position, q.pk))
    page_questions = _page_questions(participant, trial, questions)
    return ParticipantPage(
        number=number,
        total=page_count(participant),
        trial=trial,
        block=trial.block,
        block_intro=_opens_block(participant, number, trial),
        clips=_page_clips(participant, trial, asks=bool(questions)),
        questions=page_questions,
        asl=_page_asl(participant, trial, page_questions),
    )


def _opens_block(participant: Participant, number: int, trial: Trial) -> bool:
    """Return whether page *number* is the first of a block with an introduction."""
    if not trial.block.intro_text:
        return False
    if number == 1:
        return True
    previous = participant.schedule[number - 2].get("trial")
    same_block = Trial.objects.filter(study=participant.study, key=previous, block=trial.block)
    return previous is None or not same_block.order_by().exists()


def _page_clips(participant: Participant, trial: Trial, asks: bool) -> tuple[PageClip, ...]:
    """Return the clips the participant is shown on *trial* (one query), in their order."""
    if not (trial.item_id and trial.condition_a_id):
        return ()
    conditions = [c for c in presented_conditions(participant, trial) if c is not None]
    ready = Stimulus.objects.filter(
        item_id=trial.item_id, condition__in=conditions, status=Stimulus.Status.READY
    )
    stimuli = {s.condition_id: s for s in ready.select_related("upload").order_by()}
    single = _("Clip") if asks else _("Example clip")
    return tuple(
        _clip(
            number,
            _("Clip %(number)s") % {"number": number} if len(conditions) == 2 else single,
            stimuli.get(c.pk),
        )
        for number, c in enumerate(conditions, 1)
    )


def _clip(number: int, label: str, stimulus: Stimulus | None) -> PageClip:
    """Return clip *number* showing *stimulus* (none yet: no files)."""
    if stimulus is None:
        return PageClip(number=number, label=label)
    return PageClip(
        number=number,
        label=label,
        video_url=stimulus.video_url,
        poster_url=stimulus.poster_url,
        width=stimulus.width or 640,
        height=stimulus.height or 480,
    )


def _page_questions(
    participant: Participant, trial: Trial, questions: list[Question]
) -> tuple[PageQuestion, ...]:
    """Return *questions* with their options and the participant's answers so far."""
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
    return tuple(
        _page_question(participant, question, responses.get(question.pk), personal)
        for question in questions
    )


def _page_question(
    participant: Participant, question: Question, response: Response | None, personal: dict
) -> PageQuestion:
    """Return *question* with its options, its answer and a signed answer's video link."""
    if question.is_personal:
        answer = personal.get(question.pk, "")
    else:
        answer = _answer_text(response, question)
    options = tuple(sorted(question.options.all(), key=lambda o: (o.position, o.value)))
    video_url = ""
    if response is not None and response.video:
        video_url = reverse("participant_answer_video", args=[participant.token, response.pk])
    return PageQuestion(question, options, answer, video_url)


def _page_asl(participant: Participant, trial: Trial, questions: tuple[PageQuestion, ...]) -> dict:
    """Return the ASL versions of the page's texts, for a participant reading ASL first."""
    if participant.language != Participant.Language.ASL_ENGLISH:
        return {}
    objects = [trial, trial.block, *(q.question for q in questions)]
    objects += [option for q in questions for option in q.options]
    return with_templates(asl_videos(objects), participant.study, objects, ui=True)


def study_asl(study: Study, language: str) -> dict:
    """Return the study's own ASL videos (welcome, consent, thank-you) for *language*."""
    if language != Participant.Language.ASL_ENGLISH:
        return {}
    return with_templates(asl_videos([study]), study, [study])
