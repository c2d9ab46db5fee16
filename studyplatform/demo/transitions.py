"""Define the transition study seed 001 §5.2.3 proposes (spec 04 "Perceptual evaluation").

Pairs of videos of the same sign pair, joined by different transition models, judged on
the 5-point comparative scale; and "What is the virtual interpreter saying?" on single
clips, scored by the intelligibility scorer. The four models: linear and simple Hermite
(seed 001's baselines), the data-driven Hermite (seed 001) and seed 004's concatenation
with blending.
"""

from typing import Any

from stimuli import attention_checks, balanced_pair_assignment
from studyplatform.demo.common import about_you, asl_fluency, definition, numbered, scale

SLUG = "sign-transitions"
# Two sign pairs whose arms travel far between the signs (the simulated database's
# largest transitions), so the models differ visibly.
SIGN_PAIRS = (("P1", "WHERE SURPRISE"), ("P2", "INFORM-YOU SEARCH"))
# Seed 001 §4.2: captured transitions lasted 0.54 s on average.
COMMON = {"transition_ms": 500.0, "rate_hz": 30.0}

CONDITIONS = (
    {
        "key": "linear",
        "label": "Linear",
        "description": "Straight-line interpolation of every arm angle (seed 001 baseline).",
        "parameters": {"transition": "linear", **COMMON},
    },
    {
        "key": "simple-hermite",
        "label": "Simple Hermite",
        "description": (
            "A Hermite curve whose tangents follow the signs, half the gap long (seed 001 "
            "baseline)."
        ),
        "parameters": {"transition": "simple_hermite", **COMMON},
    },
    {
        "key": "hermite",
        "label": "Data-driven Hermite",
        "is_simulated": True,
        "description": (
            "The nearest recorded transition, skewed into the gap (seed 001). No captures "
            "ship with SignStudy: the built-in database holds simulated captures, so this "
            "condition is labelled simulated until a database of recordings is set."
        ),
        "parameters": {"transition": "hermite", **COMMON},
    },
    {
        "key": "blended",
        "label": "Blended",
        "description": (
            "Each sign made from rest and back, overlapped and blended linearly (seed 004)."
        ),
        "parameters": {"transition": "blended", **COMMON},
    },
)


def transitions_study() -> dict[str, Any]:
    """Return the definition of the 4 transition models × 2 sign pairs study."""
    block, page = about_you()
    questions = numbered(
        [
            asl_fluency(),
            {
                "key": "saying",
                "kind": "intelligibility",
                "text": "What is the virtual interpreter saying?",
                "help_text": "Type the signs in English words.",
            },
            {
                "key": "compare-transitions",
                "kind": "comparative",
                "text": "Which clip moves better from the first sign to the second?",
                "help_text": "Choose the middle point if both look the same.",
                "options": scale(
                    [
                        "Clip 1 a lot better",
                        "Clip 1 a little better",
                        "Both the same",
                        "Clip 2 a little better",
                        "Clip 2 a lot better",
                    ]
                ),
            },
        ]
    )
    blocks = numbered(
        [
            block,
            {
                "key": "understanding",
                "kind": "trials",
                "title": "Part 1: what is signed?",
                "intro_text": "Watch each clip and type what the signer says.",
            },
            {
                "key": "comparisons",
                "kind": "trials",
                "title": "Part 2: compare the movements",
                "randomize_order": True,
            },
        ]
    )
    keys = [condition["key"] for condition in CONDITIONS]
    items = [key for key, _ in SIGN_PAIRS]
    trials = [page]
    # Each participant reads each sign pair once, under conditions the study's rotation
    # moves on from one participant to the next (a Latin square over participants).
    for index, item in enumerate(items):
        trials.append(
            {
                "key": f"say-{item.lower()}",
                "block": "understanding",
                "kind": "intelligibility",
                "item": item,
                "condition_a": keys[index],
                "questions": ["saying"],
            }
        )
    for index, (item, first, second) in enumerate(balanced_pair_assignment(keys, items), 1):
        trials.append(
            {
                "key": f"cmp-{index:02d}",
                "block": "comparisons",
                "kind": "comparative",
                "item": item,
                "condition_a": first,
                "condition_b": second,
                "questions": ["compare-transitions"],
            }
        )
    for number, (item, first, second) in enumerate(attention_checks(keys, items, 1, seed=3), 1):
        trials.append(
            {
                "key": f"attention-{number}",
                "block": "comparisons",
                "kind": "comparative",
                "item": item,
                "condition_a": first,
                "condition_b": second,
                "questions": ["compare-transitions"],
                "is_attention_check": True,
                "expected_answer": "3",
            }
        )
    return definition(
        {
            "slug": SLUG,
            "title": "Transitions between signs (demo)",
            "description": (
                "Four ways of moving from one sign to the next, compared on two sign pairs: "
                "linear, simple Hermite, data-driven Hermite (after Angare 2021) and "
                "blending (after Gürel 2009)."
            ),
            "status": "open",
            "rotate_conditions": True,
            "consent_text": (
                "This study shows short signed clips, asks what they say and which moves "
                "better between signs. It takes about 5 minutes. Continuing means you agree "
                "to take part."
            ),
            "completion_code": "TRANS-DEMO",
        },
        conditions=numbered(list(CONDITIONS)),
        items=numbered(
            [{"key": key, "kind": "sign_pair", "text": text} for key, text in SIGN_PAIRS]
        ),
        questions=questions,
        blocks=blocks,
        trials=numbered(trials),
    )
