"""Test the balanced pair assignment against the design of seed 000 §5.3 (Table 5.1)."""

from collections import Counter
from itertools import combinations, pairwise

import pytest

from stimuli import (
    all_ordered_pairs,
    attention_checks,
    balanced_pair_assignment,
    latin_square,
    rotate_for_participant,
    shuffled,
)

CONDITIONS = ["mocap", "variable", "constant", "normalized"]
WORDS = ["GUITAR", "HEAVEN", "ARREST", "ELEPHANT", "PSYCHIATRY", "DAVID", "MICHAEL", "VICTOR"]


def test_spec_02_design_has_48_pages_each_ordered_pair_4_times():
    pages = balanced_pair_assignment(CONDITIONS, WORDS)
    assert len(pages) == 48
    ordered = Counter((a, b) for _, a, b in pages)
    assert len(ordered) == 12
    assert set(ordered.values()) == {4}


def test_every_word_meets_every_unordered_pair_once():
    pages = balanced_pair_assignment(CONDITIONS, WORDS)
    cells = Counter((word, frozenset((a, b))) for word, a, b in pages)
    assert len(cells) == 8 * 6
    assert set(cells.values()) == {1}
    assert {pair for _, pair in cells} == {frozenset(p) for p in combinations(CONDITIONS, 2)}


def test_each_condition_is_clip_1_equally_often():
    firsts = Counter(a for _, a, _ in balanced_pair_assignment(CONDITIONS, WORDS))
    assert set(firsts.values()) == {12}


def test_odd_number_of_items_is_rejected_with_reason():
    with pytest.raises(ValueError, match="even number of items; got 3"):
        balanced_pair_assignment(CONDITIONS, WORDS[:3])


@pytest.mark.parametrize(
    "conditions, items",
    [(["a"], ["x", "y"]), (["a", "a"], ["x", "y"]), (["a", "b"], ["x", "x"])],
)
def test_degenerate_designs_are_rejected(conditions, items):
    with pytest.raises(ValueError):
        balanced_pair_assignment(conditions, items)


def test_all_ordered_pairs_and_attention_checks():
    pages = all_ordered_pairs(CONDITIONS, WORDS)
    assert len(pages) == 8 * 12 and len(set(pages)) == len(pages)
    checks = attention_checks(CONDITIONS, WORDS, 4, seed=1)
    assert len(checks) == 4 and all(a == b for _, a, b in checks)
    assert checks == attention_checks(CONDITIONS, WORDS, 4, seed=1)


@pytest.mark.parametrize("n", [2, 3, 4, 5, 6])
def test_latin_square_is_latin_and_balanced_for_carry_over(n):
    square = latin_square(n)
    assert all(sorted(row) == list(range(n)) for row in square)
    assert all(sorted(column) == list(range(n)) for column in zip(*square, strict=True))
    if n % 2 == 0:
        follows = Counter((a, b) for row in square for a, b in pairwise(row))
        assert set(follows.values()) == {1} and len(follows) == n * (n - 1)


@pytest.mark.parametrize("participants", [4, 8, 12])
def test_rotation_is_balanced_over_any_multiple_of_the_square(participants):
    pages = balanced_pair_assignment(CONDITIONS, WORDS)
    seen = Counter()
    for p in range(participants):
        mine = rotate_for_participant(pages, CONDITIONS, p)
        # Each participant's own set keeps the design's balance.
        assert set(Counter((a, b) for _, a, b in mine).values()) == {4}
        seen.update(mine)
    cells = {(w, a, b) for w in WORDS for a in CONDITIONS for b in CONDITIONS if a != b}
    # Every word meets every unordered pair equally often.
    pairs = Counter((w, frozenset((a, b))) for (w, a, b), c in seen.items() for _ in range(c))
    assert len(set(pairs.values())) == 1
    assert set(seen) <= cells


def test_schedules_are_reproducible_from_a_seed():
    pages = balanced_pair_assignment(CONDITIONS, WORDS)
    assert shuffled(pages, 7) == shuffled(pages, 7) != shuffled(pages, 8)
    assert sorted(shuffled(pages, 7)) == sorted(pages)
