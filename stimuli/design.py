"""Turn conditions × items into the trials of a study design (spec 02 "The study")."""

from collections.abc import Sequence
from itertools import combinations


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
