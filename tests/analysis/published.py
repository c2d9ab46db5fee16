"""Build tidy response rows that reproduce published tables, for golden tests.

Sources: seed 000 (Wheatland 2016) Table 5.2; seed 003 (McDonald et al.) Table 3.
Only the counts are published; how wins spread over participants is not, so wins are
spread evenly over the judgement slots (Bresenham), which leaves the totals exact.
"""

import pandas as pd

from analysis.tidy import REQUIRED_COLUMNS

COLUMNS = list(REQUIRED_COLUMNS)

# Seed 000 Table 5.2: (type 1, type 2) → (# type 1, # type 2), 80 judgements per pair.
TABLE_5_2 = {
    ("Constant", "Mocap"): (25, 55),
    ("Constant", "Normalized"): (26, 54),
    ("Constant", "Variable"): (24, 56),
    ("Mocap", "Normalized"): (47, 33),
    ("Mocap", "Variable"): (37, 43),
    ("Normalized", "Variable"): (32, 48),
}
WORDS = ["GUITAR", "HEAVEN", "ARREST", "ELEPHANT", "PSYCHIATRY", "DAVID", "MICHAEL", "VICTOR"]

# Seed 003 Table 3: sentence → (control, spine movement), 22 participants.
TABLE_3 = {"S1": (11, 11), "S2": (4, 18), "S3": (16, 6), "S4": (3, 19), "S5": (13, 9)}


def _spread(wins: int, total: int) -> list[bool]:
    """Return *total* booleans with *wins* True, spread evenly."""
    return [(j + 1) * wins // total > j * wins // total for j in range(total)]


def _row(**values) -> dict:
    row = dict.fromkeys(COLUMNS, "")
    row.update(values)
    return row


def table_5_2_rows(participants: int = 10) -> pd.DataFrame:
    """Return 10 participants × 48 pages whose pair totals equal seed 000 Table 5.2."""
    rows = []
    for (a, b), (a_wins, b_wins) in TABLE_5_2.items():
        total = participants * len(WORDS)
        assert a_wins + b_wins == total
        outcome = iter(_spread(a_wins, total))
        for participant in range(participants):
            for index, word in enumerate(WORDS):
                clip1, clip2 = (a, b) if (index + participant) % 2 == 0 else (b, a)
                rows.append(
                    _row(
                        participant=f"P{participant + 1:02d}",
                        study="fingerspelling",
                        block="comparisons",
                        trial=f"{word}-{a}-{b}",
                        item=word,
                        kind="pairwise",
                        condition_a=clip1,
                        condition_b=clip2,
                        chosen=a if next(outcome) else b,
                        question="most-natural",
                        rt_ms="1500",
                    )
                )
    return pd.DataFrame(rows, columns=COLUMNS)


def table_3_rows() -> pd.DataFrame:
    """Return 22 participants × 5 sentences whose counts equal seed 003 Table 3."""
    rows = []
    for sentence, (control, spine) in TABLE_3.items():
        for participant, prefers_control in enumerate(_spread(control, control + spine)):
            clip1, clip2 = ("control", "spine") if participant % 2 else ("spine", "control")
            rows.append(
                _row(
                    participant=f"P{participant + 1:02d}",
                    study="spine",
                    block="part2",
                    trial=f"prefer-{sentence}",
                    item=sentence,
                    kind="pairwise",
                    condition_a=clip1,
                    condition_b=clip2,
                    chosen="control" if prefers_control else "spine",
                    question="preferred",
                )
            )
    return pd.DataFrame(rows, columns=COLUMNS)
