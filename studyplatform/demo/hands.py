"""Define a hand-dimensionality study (spec 05): full vs reduced vs reconstructed hands.

Fingerspelled words shown with every DOF of the hand, with seed 002's reduced DOFs
(range < 5°, rmsd < 0.5) and rebuilt from three markers by seed 000's LWR. Part 1 asks
which word is spelled (scored automatically); part 2 compares the hands in pairs.
"""

from typing import Any

from stimuli import balanced_pair_assignment
from studyplatform.demo.common import about_you, asl_fluency, definition, numbered

SLUG = "hand-dimensionality"
WORDS = ("CAB", "HIKE")
FILMING = {"view": "hand", "rate_hz": 30.0}

CONDITIONS = (
    {
        "key": "full",
        "label": "Full hand",
        "description": "Every DOF of the hand, as the engine spells the word.",
        "parameters": {"hand": "full", **FILMING},
    },
    {
        "key": "reduced",
        "label": "Reduced DOFs",
        "description": (
            "Seed 002's reduction on the word's own motion: digit curves moving under 5° "
            "fixed at their mean, curves within rmsd 0.5 of another rebuilt from it."
        ),
        "parameters": {"hand": "reduced", "hand_range_deg": 5.0, "hand_rmsd": 0.5, **FILMING},
    },
    {
        "key": "reconstructed",
        "label": "Three markers",
        "description": (
            "The digits rebuilt from the three most influential markers by locally weighted "
            "regression (seed 000 ch. 3), the engine's alphabet as the pose database."
        ),
        "parameters": {"hand": "reconstructed", "hand_markers": 3, "hand_method": "lwr", **FILMING},
    },
)


def hands_study() -> dict[str, Any]:
    """Return the definition of the 3 hands × 2 words study."""
    block, page = about_you()
    questions = numbered(
        [
            asl_fluency(),
            {
                "key": "which-word",
                "kind": "intelligibility",
                "text": "Which word is fingerspelled?",
                "help_text": "Type the word.",
            },
            {"key": "more-natural", "kind": "pairwise", "text": "Which hand moves more naturally?"},
        ]
    )
    blocks = numbered(
        [
            block,
            {"key": "reading", "kind": "trials", "title": "Part 1: which word?"},
            {
                "key": "comparisons",
                "kind": "trials",
                "title": "Part 2: compare the hands",
                "randomize_order": True,
            },
        ]
    )
    keys = [condition["key"] for condition in CONDITIONS]
    trials = [page]
    # Each participant reads each word once; the rotation moves the conditions on.
    for index, word in enumerate(WORDS):
        trials.append(
            {
                "key": f"read-{word.lower()}",
                "block": "reading",
                "kind": "intelligibility",
                "item": word,
                "condition_a": keys[index],
                "questions": ["which-word"],
            }
        )
    for index, (word, first, second) in enumerate(balanced_pair_assignment(keys, WORDS), 1):
        trials.append(
            {
                "key": f"cmp-{index:02d}",
                "block": "comparisons",
                "kind": "pairwise",
                "item": word,
                "condition_a": first,
                "condition_b": second,
                "questions": ["more-natural"],
            }
        )
    return definition(
        {
            "slug": SLUG,
            "title": "Full, reduced and reconstructed hands (demo)",
            "description": (
                "Fingerspelled words with the full hand, with fewer DOFs (after Jörg and "
                "O'Sullivan) and rebuilt from three markers (after Wheatland 2016, ch. 3)."
            ),
            "status": "open",
            "rotate_conditions": True,
            "consent_text": (
                "This study shows short fingerspelled clips, asks which word is spelled and "
                "which hand moves more naturally. It takes about 3 minutes. Continuing "
                "means you agree to take part."
            ),
            "completion_code": "HANDS-DEMO",
        },
        conditions=numbered(list(CONDITIONS)),
        items=numbered([{"key": word, "kind": "word", "text": word} for word in WORDS]),
        questions=questions,
        blocks=blocks,
        trials=numbered(trials),
    )
