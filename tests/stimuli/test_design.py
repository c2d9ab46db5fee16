"""Test the balanced pair assignment against the design of seed 000 §5.3 (Table 5.1)."""

from collections import Counter
from itertools import combinations

import pytest

from stimuli import balanced_pair_assignment

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
