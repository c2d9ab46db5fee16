"""Summarize a study's design for the builder: pages, pair counts, an estimated duration."""

from collections import Counter
from dataclasses import dataclass

from studyplatform.lib.schedule import build_schedule
from studyplatform.lib.stimuli import identical_clips
from studyplatform.models import Block, Condition, Item, Stimulus, Study, Trial

# A rough allowance per answer, beyond watching the clips; the summary says so.
ANSWER_S = 5.0
INFO_PAGE_S = 15.0
# A clip length assumed before any clip of the study is rendered.
DEFAULT_CLIP_S = 3.0


@dataclass(frozen=True)
class DesignSummary:
    """What one participant meets, and how the comparisons are balanced."""

    pages: int
    pages_by_block: tuple[tuple[str, int], ...]
    condition_counts: tuple[tuple[str, int], ...]
    pair_counts: tuple[tuple[str, str, int], ...]
    attention_checks: int
    rotated: bool
    minutes: float
    clips_known: int
    clips_total: int
    assumed_clip_s: float
    identical: tuple[tuple[Item, tuple[Condition, ...]], ...]

    @property
    def balanced(self) -> bool:
        """Return whether every condition and every ordered pair appear equally often."""
        conditions = {count for _, count in self.condition_counts}
        pairs = {count for _, _, count in self.pair_counts}
        return len(conditions) <= 1 and len(pairs) <= 1


def summarize_design(study: Study) -> DesignSummary:
    """Return the summary of *study*'s pages as they stand (any participant's count)."""
    trials = {
        t.key: t
        for t in Trial.objects.filter(study=study)
        .select_related("block", "condition_a", "condition_b")
        .prefetch_related("questions")
    }
    schedule = build_schedule(study, seed=0)
    blocks, conditions, pairs = _counts(trials.values())
    lengths = {
        (s.condition_id, s.item_id): s.duration_ms / 1000
        for s in Stimulus.objects.filter(condition__study=study, status=Stimulus.Status.READY)
        if s.duration_ms
    }
    assumed = sum(lengths.values()) / len(lengths) if lengths else DEFAULT_CLIP_S
    seconds, known, total = _duration(schedule, trials, lengths, assumed)
    return DesignSummary(
        pages=len(schedule),
        pages_by_block=tuple(
            (str(block), count)
            for block, count in sorted(blocks.items(), key=lambda b: b[0].position)
        ),
        condition_counts=tuple(sorted(conditions.items())),
        pair_counts=tuple((a, b, n) for (a, b), n in sorted(pairs.items())),
        attention_checks=sum(t.is_attention_check for t in trials.values()),
        rotated=study.rotate_conditions,
        minutes=seconds / 60,
        clips_known=known,
        clips_total=total,
        assumed_clip_s=assumed,
        identical=tuple((item, tuple(same)) for item, same in identical_clips(study)),
    )


def _counts(trials) -> tuple[Counter, Counter, Counter]:
    """Count pages per block, and the study's pages per condition and per pair."""
    blocks: Counter = Counter()
    conditions: Counter = Counter()
    pairs: Counter = Counter()
    for trial in trials:
        blocks[trial.block] += 1
        if trial.block.kind != Block.Kind.TRIALS or trial.is_attention_check:
            continue
        for condition in (trial.condition_a, trial.condition_b):
            if condition is not None:
                conditions[str(condition)] += 1
        if trial.condition_b is not None:
            pairs[(str(trial.condition_a), str(trial.condition_b))] += 1
    return blocks, conditions, pairs


def _duration(schedule, trials: dict, lengths: dict, assumed: float) -> tuple[float, int, int]:
    """Return a participant's expected seconds, and how many of the clips shown have a
    known length out of all (the others are assumed *assumed* seconds long)."""
    seconds, known, total = 0.0, 0, 0
    for entry in schedule:
        trial = trials[entry["trial"]]
        questions = len(trial.questions.all())
        seconds += ANSWER_S * questions if questions else INFO_PAGE_S
        for condition_id in (trial.condition_a_id, trial.condition_b_id):
            if condition_id is not None and trial.item_id is not None:
                total += 1
                length = lengths.get((condition_id, trial.item_id))
                known += length is not None
                seconds += assumed if length is None else length
    return seconds, known, total
