"""Plan a study's pages from conditions × items and a design (spec 06 "Trial templates").

:func:`plan_pages` is what the admin's design builder creates trials from: the main
pages of the chosen design, practice pages on practice items, and identical-clip
attention checks. :func:`summarize_pages` counts what a plan shows, for the builder's
summary.
"""

from collections import Counter
from dataclasses import dataclass, field
from enum import StrEnum

from stimuli.design import all_ordered_pairs, attention_checks, balanced_pair_assignment


class Design(StrEnum):
    """The designs the builder offers."""

    ALL_PAIRS = "all_pairs"
    BALANCED_PAIRS = "balanced_pairs"
    RATINGS = "ratings"
    LATIN_SQUARE = "latin_square"

    @property
    def label(self) -> str:
        """Return how the admin names the design."""
        return DESIGN_LABELS[self]

    @property
    def compares_pairs(self) -> bool:
        """Return whether its pages show two clips (else one clip to rate)."""
        return self in (Design.ALL_PAIRS, Design.BALANCED_PAIRS)


DESIGN_LABELS = {
    Design.ALL_PAIRS: "All ordered pairs: every item with every pair of conditions, both orders",
    Design.BALANCED_PAIRS: (
        "Balanced assignment: every item meets every pair once, each order on half the "
        "items (seed 000 §5.3; needs an even number of items)"
    ),
    Design.RATINGS: "Single-clip ratings: every item in every condition",
    Design.LATIN_SQUARE: (
        "Latin-square rotation: single-clip ratings, each item once per participant, its "
        "condition rotated across participants"
    ),
}


class DesignError(ValueError):
    """A design that cannot be built from the chosen conditions and items."""


@dataclass(frozen=True)
class DesignSpec:
    """What the researcher chose: a design over conditions × items, practice, checks.

    *seed* fixes which item and condition each attention check shows.
    """

    design: Design
    conditions: tuple[str, ...]
    items: tuple[str, ...]
    practice_items: tuple[str, ...] = ()
    attention_checks: int = 0
    seed: int = 0

    def __post_init__(self) -> None:
        object.__setattr__(self, "design", Design(self.design))
        if len(set(self.conditions)) != len(self.conditions):
            raise DesignError("A condition is chosen twice.")
        if len(set(self.items)) != len(self.items):
            raise DesignError("An item is chosen twice.")
        if not self.items:
            raise DesignError("Choose at least one item.")
        if self.design.compares_pairs and len(self.conditions) < 2:
            raise DesignError("A comparison of clips needs at least two conditions.")
        if not self.conditions:
            raise DesignError("Choose at least one condition.")
        if self.attention_checks < 0:
            raise DesignError("The number of attention checks cannot be negative.")

    def to_dict(self) -> dict:
        """Return the spec as JSON-ready data (stored with the study)."""
        return {
            "design": self.design.value,
            "conditions": list(self.conditions),
            "items": list(self.items),
            "practice_items": list(self.practice_items),
            "attention_checks": self.attention_checks,
            "seed": self.seed,
        }

    @classmethod
    def from_dict(cls, data: dict) -> "DesignSpec":
        """Return the spec stored by :meth:`to_dict`."""
        return cls(
            design=data["design"],
            conditions=tuple(data["conditions"]),
            items=tuple(data["items"]),
            practice_items=tuple(data.get("practice_items", ())),
            attention_checks=int(data.get("attention_checks", 0)),
            seed=int(data.get("seed", 0)),
        )


@dataclass(frozen=True)
class PlannedPage:
    """One page of the plan: an item in one condition, or in two (clip 1, clip 2)."""

    item: str
    condition_a: str
    condition_b: str | None = None
    practice: bool = False
    attention_check: bool = False


def _main_pages(spec: DesignSpec) -> list[PlannedPage]:
    conditions, items = spec.conditions, spec.items
    if spec.design is Design.ALL_PAIRS:
        return [PlannedPage(i, a, b) for i, a, b in all_ordered_pairs(conditions, items)]
    if spec.design is Design.BALANCED_PAIRS:
        try:
            triples = balanced_pair_assignment(conditions, items)
        except ValueError as error:
            raise DesignError(str(error)) from None
        return [PlannedPage(i, a, b) for i, a, b in triples]
    if spec.design is Design.RATINGS:
        return [PlannedPage(item, condition) for item in items for condition in conditions]
    # Latin square: item i in condition i mod k; each participant's row of the square
    # relabels the conditions (stimuli.rotate_for_participant), so over every k
    # participants each item is shown in every condition once.
    if len(items) % len(conditions):
        raise DesignError(
            f"A Latin square shows each condition equally often only when the number of "
            f"items ({len(items)}) is a multiple of the number of conditions "
            f"({len(conditions)})."
        )
    return [PlannedPage(item, conditions[i % len(conditions)]) for i, item in enumerate(items)]


def _practice_pages(spec: DesignSpec) -> list[PlannedPage]:
    conditions = spec.conditions
    pages = []
    for index, item in enumerate(spec.practice_items):
        first = conditions[index % len(conditions)]
        if spec.design.compares_pairs:
            second = conditions[(index + 1) % len(conditions)]
            pages.append(PlannedPage(item, first, second, practice=True))
        else:
            pages.append(PlannedPage(item, first, practice=True))
    return pages


def plan_pages(spec: DesignSpec) -> tuple[PlannedPage, ...]:
    """Return the practice pages, then the main pages with the attention checks last.

    On a comparison design an attention check shows one condition's clip twice (its
    answer: no difference); on a rating design it is one clip whose page instructs the
    answer. Item and condition of each check are drawn from *spec.seed*.
    """
    drawn = attention_checks(spec.conditions, spec.items, spec.attention_checks, spec.seed)
    checks = [
        PlannedPage(item, a, b if spec.design.compares_pairs else None, attention_check=True)
        for item, a, b in drawn
    ]
    return (*_practice_pages(spec), *_main_pages(spec), *checks)


@dataclass(frozen=True)
class PlanSummary:
    """What a plan shows: pages, and how often each condition and ordered pair appear."""

    pages: int
    practice_pages: int
    attention_checks: int
    clips: int
    condition_counts: dict[str, int] = field(default_factory=dict)
    pair_counts: dict[tuple[str, str], int] = field(default_factory=dict)
    item_counts: dict[str, int] = field(default_factory=dict)


def summarize_pages(pages: tuple[PlannedPage, ...]) -> PlanSummary:
    """Count the main pages' conditions, ordered pairs and items (practice and checks apart)."""
    main = [p for p in pages if not (p.practice or p.attention_check)]
    conditions: Counter = Counter()
    for page in main:
        conditions[page.condition_a] += 1
        if page.condition_b is not None:
            conditions[page.condition_b] += 1
    pairs = Counter((p.condition_a, p.condition_b) for p in main if p.condition_b is not None)
    return PlanSummary(
        pages=len(pages),
        practice_pages=sum(p.practice for p in pages),
        attention_checks=sum(p.attention_check for p in pages),
        clips=sum(1 if p.condition_b is None else 2 for p in pages),
        condition_counts=dict(conditions),
        pair_counts=dict(pairs),
        item_counts=dict(Counter(p.item for p in main)),
    )
