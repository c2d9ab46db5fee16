"""Turn conditions × items into the trials of a study design (spec 02 "The study")."""

from collections.abc import Sequence
from itertools import combinations

import numpy as np


def balanced_pair_assignment(
    conditions: Sequence[str], items: Sequence[str]
) -> list[tuple[str, str, str]]:
    """Return (item, clip-1 condition, clip-2 condition) triples for a pairwise study.

    Every item meets every unordered pair of conditions once, and each pair is shown in
    both orders equally often across items (seed 000 §5.3, Table 5.1: 8 words × 6 pairs
    = 48 pages, each ordered pair 4 times). Orders alternate along the item and pair
    indices, so across items each condition is also first equally often.
    """
    if len(set(conditions)) != len(conditions) or len(conditions) < 2:
        raise ValueError("A pairwise design needs at least two distinct conditions.")
    if len(set(items)) != len(items):
        raise ValueError("Items must be distinct.")
    if len(items) % 2:
        raise ValueError(
            f"Each order of a pair can only appear equally often with an even number of "
            f"items; got {len(items)}."
        )
    assignment = []
    for item_index, item in enumerate(items):
        for pair_index, (first, second) in enumerate(combinations(conditions, 2)):
            if (item_index + pair_index) % 2:
                first, second = second, first
            assignment.append((item, first, second))
    return assignment


def all_ordered_pairs(
    conditions: Sequence[str], items: Sequence[str]
) -> list[tuple[str, str, str]]:
    """Return every (item, clip-1 condition, clip-2 condition) with the two differing.

    The full comparison design: each item meets every ordered pair of conditions.
    """
    return [(item, a, b) for item in items for a in conditions for b in conditions if a != b]


def latin_square(n: int) -> list[list[int]]:
    """Return a balanced Latin square of order *n* (Williams design), as row lists.

    Every index appears once per row and column, and for even *n* every index follows
    every other exactly once across rows (first-order carry-over balance).
    """
    if n < 1:
        raise ValueError("A Latin square needs at least one condition.")
    first, low, high = [0], 1, n - 1
    while len(first) < n:
        first.append(low)
        low += 1
        if len(first) < n:
            first.append(high)
            high -= 1
    return [[(value + row) % n for value in first] for row in range(n)]


def rotate_for_participant(
    pages: Sequence[tuple[str, str, str]], conditions: Sequence[str], participant: int
) -> list[tuple[str, str, str]]:
    """Return the pages with conditions relabelled by row *participant* of a Latin square.

    Row r maps condition i to condition ``square[r][i]``: over any multiple of the
    square's order of participants, every item is shown in every condition at each clip
    position equally often and meets every unordered pair equally often, while each
    participant's own set keeps the design's balance. Which order a pair is shown in is
    not balanced per item by the rotation (a row keeps the differences between condition
    indices); randomized clip positions balance it in expectation.
    """
    square = latin_square(len(conditions))
    row = square[participant % len(conditions)]
    rename = {conditions[i]: conditions[row[i]] for i in range(len(conditions))}
    return [(item, rename[a], rename[b]) for item, a, b in pages]


def shuffled(pages: Sequence, seed: int) -> list:
    """Return *pages* in a random order reproducible from *seed*."""
    order = np.random.default_rng(seed).permutation(len(pages))
    return [pages[i] for i in order]


def attention_checks(
    conditions: Sequence[str], items: Sequence[str], count: int, seed: int
) -> list[tuple[str, str, str]]:
    """Return *count* identical-clip pairs (item, c, c): the answer is "no difference"."""
    rng = np.random.default_rng(seed)
    checks = []
    for _ in range(count):
        item = items[int(rng.integers(len(items)))]
        condition = conditions[int(rng.integers(len(conditions)))]
        checks.append((item, condition, condition))
    return checks
