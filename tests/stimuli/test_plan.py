"""Test the design builder's plans: each design's pages, practice, checks, and their counts."""

from collections import Counter

import pytest

from stimuli import latin_square, rotate_for_participant
from stimuli.plan import Design, DesignError, DesignSpec, plan_pages, summarize_pages

CONDITIONS = ("constant", "variable", "normalized")
ITEMS = ("CAT", "DOG", "BIRD", "FISH", "COW", "PIG")


def spec(design, conditions=CONDITIONS, items=ITEMS, **extra) -> DesignSpec:
    return DesignSpec(design=design, conditions=conditions, items=items, **extra)


def test_all_ordered_pairs_shows_each_item_with_every_ordered_pair_once():
    pages = plan_pages(spec(Design.ALL_PAIRS))
    assert len(pages) == len(ITEMS) * 3 * 2
    cells = Counter((p.item, p.condition_a, p.condition_b) for p in pages)
    assert set(cells.values()) == {1}
    assert all(p.condition_a != p.condition_b for p in pages)
    summary = summarize_pages(pages)
    assert set(summary.pair_counts.values()) == {len(ITEMS)} and len(summary.pair_counts) == 6


def test_balanced_assignment_meets_each_pair_once_per_item_and_balances_orders():
    pages = plan_pages(spec(Design.BALANCED_PAIRS))
    assert len(pages) == len(ITEMS) * 3
    unordered = Counter((p.item, frozenset((p.condition_a, p.condition_b))) for p in pages)
    assert set(unordered.values()) == {1}
    assert set(summarize_pages(pages).pair_counts.values()) == {len(ITEMS) // 2}


def test_balanced_assignment_refuses_an_odd_number_of_items():
    with pytest.raises(DesignError, match="even number of items; got 5"):
        plan_pages(spec(Design.BALANCED_PAIRS, items=ITEMS[:5]))


def test_ratings_show_every_item_in_every_condition_on_its_own():
    pages = plan_pages(spec(Design.RATINGS))
    assert len(pages) == 18 and all(p.condition_b is None for p in pages)
    assert set(summarize_pages(pages).condition_counts.values()) == {len(ITEMS)}


def test_latin_square_shows_each_item_once_and_over_k_participants_in_every_condition():
    pages = plan_pages(spec(Design.LATIN_SQUARE))
    assert [p.item for p in pages] == list(ITEMS)
    assert set(summarize_pages(pages).condition_counts.values()) == {2}
    triples = [(p.item, p.condition_a, p.condition_a) for p in pages]
    seen = Counter()
    for participant in range(len(CONDITIONS)):
        for item, condition, _ in rotate_for_participant(triples, CONDITIONS, participant):
            seen[(item, condition)] += 1
    assert len(seen) == len(ITEMS) * len(CONDITIONS) and set(seen.values()) == {1}
    assert len(latin_square(3)) == 3


def test_latin_square_needs_items_in_multiples_of_the_conditions():
    with pytest.raises(DesignError, match=r"number of items \(4\) is a multiple .* \(3\)"):
        plan_pages(spec(Design.LATIN_SQUARE, items=ITEMS[:4]))


def test_practice_comes_first_and_attention_checks_last_and_neither_is_counted():
    pages = plan_pages(
        spec(Design.BALANCED_PAIRS, practice_items=("EXAMPLE",), attention_checks=2, seed=4)
    )
    assert pages[0].practice and pages[0].item == "EXAMPLE"
    assert pages[0].condition_a != pages[0].condition_b
    checks = pages[-2:]
    assert all(p.attention_check and p.condition_a == p.condition_b for p in checks)
    summary = summarize_pages(pages)
    assert (summary.pages, summary.practice_pages, summary.attention_checks) == (21, 1, 2)
    assert sum(summary.item_counts.values()) == 18
    # The same seed draws the same checks.
    again = plan_pages(
        spec(Design.BALANCED_PAIRS, practice_items=("EXAMPLE",), attention_checks=2, seed=4)
    )
    assert again == pages


def test_rating_designs_check_attention_on_one_clip():
    pages = plan_pages(spec(Design.RATINGS, attention_checks=1))
    assert pages[-1].attention_check and pages[-1].condition_b is None


@pytest.mark.parametrize(
    ("changes", "message"),
    [
        ({"conditions": ("a",)}, "at least two conditions"),
        ({"conditions": ("a", "a")}, "condition is chosen twice"),
        ({"items": ()}, "at least one item"),
        ({"items": ("X", "X")}, "item is chosen twice"),
        ({"attention_checks": -1}, "cannot be negative"),
        ({"design": "nonsense"}, "not a valid Design"),
    ],
)
def test_impossible_specs_are_refused_with_the_reason(changes, message):
    arguments = {"design": Design.ALL_PAIRS, "conditions": CONDITIONS, "items": ITEMS, **changes}
    with pytest.raises(ValueError, match=message):
        DesignSpec(**arguments)


def test_a_spec_round_trips_through_its_dict():
    original = spec(Design.RATINGS, practice_items=("EX",), attention_checks=1, seed=9)
    assert DesignSpec.from_dict(original.to_dict()) == original
