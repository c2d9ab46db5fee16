"""Lay out every page of a study in participant order, for the researcher's preview."""

from dataclasses import dataclass, field

from django.utils.translation import gettext

from studyplatform.models import Block, Condition, Question, Stimulus, Study, Trial


@dataclass(frozen=True)
class Clip:
    """One clip slot on a page: its label, condition and rendered stimulus if any."""

    label: str
    condition: Condition
    stimulus: Stimulus | None


@dataclass(frozen=True)
class PreviewPage:
    """One page as a participant meets it, in design order (before randomization)."""

    number: int
    kind: str
    title: str
    text: str = ""
    block: Block | None = None
    trial: Trial | None = None
    clips: tuple[Clip, ...] = ()
    questions: tuple[Question, ...] = field(default_factory=tuple)


def build_preview(study: Study) -> list[PreviewPage]:
    """Return the study's pages: consent, every block's trials in order, thank-you."""
    ready = {}
    for stimulus in Stimulus.objects.filter(
        condition__study=study, status=Stimulus.Status.READY
    ).order_by("rendered_at", "pk"):
        ready[(stimulus.condition_id, stimulus.item_id)] = stimulus
    trials = (
        study.trials.select_related("block", "item", "condition_a", "condition_b")
        .prefetch_related("questions__options")
        .order_by("block__position", "block__pk", "position", "pk")
    )
    # Consent and thank-you are unnumbered, as participants see them: "Page n of N"
    # counts the pages between.
    pages = [
        PreviewPage(number=0, kind="consent", title=gettext("Consent"), text=study.consent_text)
    ]
    for trial in trials:
        clips = []
        if trial.condition_a is not None and trial.item is not None:
            two = trial.condition_b is not None
            for label, condition in (
                (gettext("Clip 1") if two else gettext("Clip"), trial.condition_a),
                (gettext("Clip 2"), trial.condition_b),
            ):
                if condition is not None:
                    stimulus = ready.get((condition.pk, trial.item_id))
                    clips.append(Clip(label=label, condition=condition, stimulus=stimulus))
        pages.append(
            PreviewPage(
                number=len(pages),
                kind=trial.kind,
                title=trial.title or trial.block.title or trial.key,
                text=trial.text,
                block=trial.block,
                trial=trial,
                clips=tuple(clips),
                questions=tuple(sorted(trial.questions.all(), key=lambda q: (q.position, q.pk))),
            )
        )
    pages.append(
        PreviewPage(number=0, kind="thanks", title=gettext("Thank you"), text=study.thank_you_text)
    )
    return pages
