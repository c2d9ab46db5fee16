"""Build a study's practice and trial pages from a design (the admin's design builder).

:func:`do_build_design` turns a :class:`stimuli.plan.DesignSpec` into one practice
block and one trial block of the study, replacing what the builder made before. It
works only on a draft, and never deletes a page somebody answered.
"""

from collections.abc import Sequence
from dataclasses import dataclass

from django.core.exceptions import ValidationError
from django.db import transaction

from stimuli.plan import Design, DesignError, DesignSpec, PlannedPage, plan_pages
from studyplatform.models import (
    AnswerOption,
    Block,
    Condition,
    Item,
    Question,
    Response,
    Study,
    Trial,
)
from studyplatform.models.design import trial_question_kinds

PAIR_QUESTION = {
    "key": "more-natural",
    "kind": "pairwise",
    "text": "Which clip looks more natural?",
}
RATING_QUESTION = {
    "key": "naturalness",
    "kind": "likert",
    "text": "How natural does the signing look?",
}
RATING_LABELS = ("Very unnatural", "Unnatural", "Neither", "Natural", "Very natural")


class DesignRejected(ValidationError):
    """A design the builder cannot build; the message says why."""


@dataclass(frozen=True)
class DesignBuilt:
    """The blocks the builder filled and how many pages each got."""

    practice_block: Block | None
    trial_block: Block
    practice_pages: int
    pages: int
    attention_checks: int
    question_created: Question | None


def _trial_kind(design: Design, questions: Sequence[Question]) -> str:
    """Return the page kind that asks *questions* and suits *design*."""
    allowed = trial_question_kinds()
    kinds = Trial.TWO_CLIP_KINDS if design.compares_pairs else Trial.ONE_CLIP_KINDS
    for kind in sorted(kinds):
        if all(q.kind in allowed[kind] for q in questions):
            return kind
    wanted = "comparison (pairwise or comparative)" if design.compares_pairs else "rating"
    names = ", ".join(f"{q.key} ({q.get_kind_display()})" for q in questions)
    raise DesignRejected(
        f"A {wanted} page cannot ask {names}: choose questions of one kind that suits the design."
    )


def _standard_question(study: Study, design: Design, allow_no_difference: bool) -> Question:
    template = PAIR_QUESTION if design.compares_pairs else RATING_QUESTION
    key = _free_key(template["key"], set(study.questions.values_list("key", flat=True)))
    position = max(study.questions.values_list("position", flat=True), default=0) + 1
    question = Question.objects.create(
        study=study,
        key=key,
        kind=template["kind"],
        text=template["text"],
        position=position,
        allow_no_difference=allow_no_difference and design.compares_pairs,
    )
    if not design.compares_pairs:
        _create_options(question, tuple(enumerate(RATING_LABELS, 1)))
    return question


def _expected_answer(kind: str, questions: Sequence[Question]) -> tuple[str, str]:
    """Return the answer an attention check expects and the instruction that asks for it."""
    if kind == Trial.Kind.PAIRWISE:
        lacking = [q.key for q in questions if not q.allow_no_difference]
        if lacking:
            raise DesignRejected(
                f"An identical-clip attention check needs 'Cannot see a difference' as an "
                f"answer; {', '.join(lacking)} does not offer it (tick it on the question)."
            )
        return Response.NO_DIFFERENCE, ""
    values = [list(q.options.order_by("value").values_list("value", "label")) for q in questions]
    if any(not options for options in values):
        raise DesignRejected("An attention check needs questions with answer options.")
    if kind == Trial.Kind.COMPARATIVE:
        return _middle_point(values), ""
    if kind == Trial.Kind.RATING:
        return _top_point(values)
    raise DesignRejected("Attention checks are built for comparison and rating pages only.")


def _middle_point(values: list[list[tuple[int, str]]]) -> str:
    """Return the comparative scales' common middle point ('the same')."""
    middles = {options[len(options) // 2][0] for options in values if len(options) % 2}
    if len(middles) != 1 or any(len(options) % 2 == 0 for options in values):
        raise DesignRejected(
            "An identical-clip attention check on a comparative scale needs an odd number "
            "of points, the middle one meaning 'the same'."
        )
    return str(middles.pop())


def _top_point(values: list[list[tuple[int, str]]]) -> tuple[str, str]:
    """Return the rating scales' common top point and the instruction to choose it."""
    highest = {options[-1] for options in values}
    if len(highest) != 1:
        raise DesignRejected(
            "An instructed attention check needs rating questions with the same top point."
        )
    value, label = highest.pop()
    return str(value), (
        f"Attention check: whatever you think of this clip, please choose “{label or value}”."
    )


def _free_key(wanted: str, taken: set[str]) -> str:
    key, number = wanted, 1
    while key in taken:
        number += 1
        key = f"{wanted}-{number}"
    return key


def _builder_blocks(study: Study, practice: bool) -> tuple[Block | None, Block]:
    """Return the builder's blocks (made before, or new ones), ordered before closing blocks."""
    made = study.design.get("blocks", {})
    blocks = {b.key: b for b in study.blocks.all()}
    taken = set(blocks)

    def block(role: str, kind: str, title: str) -> Block:
        existing = blocks.get(made.get(role, ""))
        if existing is not None:
            return existing
        key = _free_key(role, taken)
        taken.add(key)
        return Block.objects.create(
            study=study, key=key, kind=kind, title=title, randomize_order=kind == Block.Kind.TRIALS
        )

    # No title: a block's title heads its first page, and "Trials" is the builder's word,
    # not one a participant should read (a researcher may give it one).
    trial_block = block("trials", Block.Kind.TRIALS, "")
    practice_block = block("practice", Block.Kind.PRACTICE, "Practice") if practice else None
    unused = made.get("practice") if not practice else None
    if unused and unused in blocks and not blocks[unused].trials.exists():
        blocks[unused].delete()
    _place_before_closing(study, [b for b in (practice_block, trial_block) if b is not None])
    return practice_block, trial_block


def _place_before_closing(study: Study, ours: list[Block]) -> None:
    """Number the study's blocks so that *ours* come after the others, before closing ones."""
    others = [b for b in study.blocks.order_by("position", "pk") if b not in ours]
    ordered = [b for b in others if b.kind != Block.Kind.CLOSING] + ours
    ordered += [b for b in others if b.kind == Block.Kind.CLOSING]
    for position, each in enumerate(ordered, 1):
        if each.position != position:
            each.position = position
            each.save(update_fields=["position"])


def _checked_design(study: Study, spec: DesignSpec) -> tuple[list[PlannedPage], dict, dict]:
    """Return the pages *spec* plans and its conditions and items by key, or DesignRejected
    (a study no longer in draft, a design that cannot be built, a key not in the study)."""
    if study.status != Study.Status.DRAFT:
        raise DesignRejected(
            f"“{study.title}” is {study.get_status_display().lower()}: its design is locked. "
            "Set it back to draft (or duplicate it) to rebuild the design."
        )
    try:
        pages = plan_pages(spec)
    except DesignError as error:
        raise DesignRejected(str(error)) from None
    conditions = {c.key: c for c in Condition.objects.filter(study=study, key__in=spec.conditions)}
    items = {
        i.key: i for i in Item.objects.filter(study=study, key__in=spec.items + spec.practice_items)
    }
    missing = [
        k
        for k in (*spec.conditions, *spec.items, *spec.practice_items)
        if k not in conditions and k not in items
    ]
    if missing:
        raise DesignRejected(f"Not in this study: {', '.join(missing)}.")
    return pages, conditions, items


def _delete_builder_pages(study: Study) -> None:
    """Delete the pages the builder made before, unless a pilot answered them."""
    old = Trial.objects.filter(
        study=study, block__key__in=list((study.design.get("blocks") or {}).values())
    )
    answered = old.filter(responses__isnull=False).distinct().count()
    if answered:
        raise DesignRejected(
            f"{answered} of the pages this builder made have answers (from a pilot). "
            "Delete those participants first, or make a new version of the study."
        )
    old.delete()


def _ask_on_pages(questions: Sequence[Question], blocks: list) -> None:
    """Ask *questions* on every page of *blocks*."""
    Trial.questions.through.objects.bulk_create(
        Trial.questions.through(trial_id=trial.pk, question_id=question.pk)
        for trial in Trial.objects.filter(block__in=blocks)
        for question in questions
    )


def do_add_default_options(question: Question) -> int:
    """Give a question of a kind with labelled points and no options yet its kind's
    starting points (a researcher adding a Likert question typed all five by hand);
    return how many were added."""
    points = question.type.default_options(question) if question.uses_options else ()
    with transaction.atomic():
        if not points or question.options.exists():
            return 0
        _create_options(question, points)
    return len(points)


def _create_options(question: Question, points: tuple[tuple[int, str], ...]) -> None:
    """Give *question* the labelled *points* (value, label), positioned in that order."""
    AnswerOption.objects.bulk_create(
        AnswerOption(question=question, value=value, label=label, position=position)
        for position, (value, label) in enumerate(points, 1)
    )


def do_build_design(
    study: Study,
    spec: DesignSpec,
    questions: Sequence[Question] = (),
    randomize_order: bool = True,
) -> DesignBuilt:
    """Replace the builder's pages of draft *study* with those *spec* plans.

    With no *questions*, a standard one is created (a 2AFC "Which clip looks more
    natural?" or a 5-point naturalness rating). Latin-square designs switch the study's
    condition rotation on, the others off.
    """
    pages, conditions, items = _checked_design(study, spec)
    with transaction.atomic(durable=True):
        study = Study.objects.select_for_update().get(pk=study.pk)
        created = None
        if not questions:
            created = _standard_question(study, spec.design, spec.attention_checks > 0)
            questions = [created]
        kind = _trial_kind(spec.design, questions)
        expected = _expected_answer(kind, questions) if spec.attention_checks else ("", "")
        _delete_builder_pages(study)
        practice_block, trial_block = _builder_blocks(study, bool(spec.practice_items))
        taken = set(Trial.objects.filter(study=study).values_list("key", flat=True))
        trials = _make_trials(
            study, pages, kind, expected, practice_block, trial_block, taken, conditions, items
        )
        for trial in trials:
            trial.full_clean(exclude=["questions"])
        Trial.objects.bulk_create(trials)
        _ask_on_pages(questions, [b for b in (practice_block, trial_block) if b])
        trial_block.randomize_order = randomize_order
        trial_block.save(update_fields=["randomize_order"])
        study.rotate_conditions = spec.design is Design.LATIN_SQUARE
        study.design = {
            **spec.to_dict(),
            "questions": [q.key for q in questions],
            "trial_kind": kind,
            "randomize_order": randomize_order,
            "blocks": {
                "trials": trial_block.key,
                **({"practice": practice_block.key} if practice_block else {}),
            },
        }
        study.save(update_fields=["rotate_conditions", "design", "updated_at"])
    return DesignBuilt(
        practice_block=practice_block,
        trial_block=trial_block,
        practice_pages=sum(p.practice for p in pages),
        pages=len(pages),
        attention_checks=spec.attention_checks,
        question_created=created,
    )


def _make_trials(
    study,
    pages: Sequence[PlannedPage],
    kind,
    expected,
    practice_block,
    trial_block,
    taken,
    conditions,
    items,
) -> list[Trial]:
    expected_answer, instruction = expected
    trials, counters = [], {"practice": 0, "main": 0, "check": 0}
    prefix = trial_block.key
    for page in pages:
        role = "practice" if page.practice else "check" if page.attention_check else "main"
        counters[role] += 1
        wanted = {
            "practice": f"{practice_block.key if practice_block else 'practice'}-{counters[role]}",
            "main": f"{prefix}-{counters[role]:03d}",
            "check": f"{prefix}-check-{counters[role]}",
        }[role]
        key = _free_key(wanted, taken)
        taken.add(key)
        check = page.attention_check
        trials.append(
            Trial(
                study=study,
                block=practice_block if page.practice else trial_block,
                key=key,
                kind=kind,
                item=items[page.item],
                condition_a=conditions[page.condition_a],
                condition_b=conditions[page.condition_b] if page.condition_b else None,
                is_attention_check=check,
                expected_answer=expected_answer if check else "",
                text=instruction if check else "",
                position=len(trials) + 1,
            )
        )
    return trials
