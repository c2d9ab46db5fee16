"""Draw a participant's schedule: the pages they see, in order, from a stored seed.

Spec 06 "Randomization per participant with a recorded seed": blocks keep their order;
pages within a block marked *randomize order* are shuffled; the two clips of a
comparison swap sides at random when the study randomizes positions; with Latin-square
rotation the trial blocks' conditions are relabelled by the participant's row
(:func:`stimuli.rotate_for_participant`). Everything follows from the seed and the
enrollment number, and the result is stored on the participant, so the exact pages
they saw stay known even if the study is edited later.

A schedule is a list of entries ``{"trial": key, "swap": bool}``, plus ``"a"``/``"b"``
(the condition keys shown) on rotated trials.
"""

import numpy as np

from stimuli import rotate_for_participant
from studyplatform.models import Block, Study, Trial


def _check_not_first(pages: list[Trial]) -> list[Trial]:
    """Return shuffled *pages* with an attention check moved off the first place (it
    changes places with the first page that is not one): a check before any real page
    tests whether the participant has understood the task, not their attention."""
    if not pages or not pages[0].is_attention_check:
        return pages
    other = next((i for i, page in enumerate(pages) if not page.is_attention_check), None)
    if other is not None:
        pages[0], pages[other] = pages[other], pages[0]
    return pages


def build_schedule(study: Study, seed: int, enrollment: int = 0) -> list[dict]:
    """Return the schedule of the participant with *seed*, enrolled *enrollment*-th."""
    rng = np.random.default_rng(seed)
    conditions = list(study.conditions.order_by("position", "pk").values_list("key", flat=True))
    trials = (
        Trial.objects.filter(study=study)
        .select_related("block", "item", "condition_a", "condition_b")
        .order_by("block__position", "block__pk", "position", "pk")
    )
    by_block: dict[int, list[Trial]] = {}
    blocks: dict[int, Block] = {}
    for trial in trials:
        by_block.setdefault(trial.block_id, []).append(trial)
        blocks[trial.block_id] = trial.block
    schedule = []
    for block_id, pages in by_block.items():
        block = blocks[block_id]
        if block.randomize_order:
            pages = _check_not_first([pages[i] for i in rng.permutation(len(pages))])
        for trial in pages:
            entry: dict = {"trial": trial.key, "swap": False}
            two_clips = trial.kind in Trial.TWO_CLIP_KINDS and trial.condition_b_id is not None
            if two_clips and study.randomize_positions:
                entry["swap"] = bool(rng.random() < 0.5)
            rotated = (
                study.rotate_conditions
                and block.kind == Block.Kind.TRIALS
                and trial.condition_a_id is not None
                and len(conditions) > 1
            )
            if rotated:
                a = trial.condition_a.key
                b = trial.condition_b.key if trial.condition_b_id else a
                ((_, a, b),) = rotate_for_participant([("", a, b)], conditions, enrollment)
                entry["a"] = a
                if trial.condition_b_id:
                    entry["b"] = b
            schedule.append(entry)
    return schedule
