"""Define the fingerspelling timing study of seed 000 ch. 5 (spec 02 "The study")."""

from typing import Any

from stimuli import attention_checks, balanced_pair_assignment
from studyplatform.demo.common import asl_fluency, definition, numbered, scale

WORDS = ("GUITAR", "HEAVEN", "ARREST", "ELEPHANT", "PSYCHIATRY", "DAVID", "MICHAEL", "VICTOR")
# A word the signer also recorded (seed 000 App. B, objective 4) for the example clip.
EXAMPLE_WORD = "DOOR"

CONDITIONS = (
    {
        "key": "mocap",
        "label": "Motion capture",
        "is_simulated": True,
        "description": (
            "No recording ships with SignStudy: a simulated reference performance stands in "
            "for motion capture until recordings are imported (spec 02)."
        ),
        "parameters": {"timing": "mocap", "source": "simulated"},
    },
    {
        "key": "variable",
        "label": "Variable",
        "description": "Data-driven timing: naive Bayes holds, regression transitions; the "
        "built-in model, {provenance}.",
        "parameters": {"timing": "variable", "source": "simulated"},
    },
    {
        "key": "constant",
        "label": "Constant",
        "description": "243 ms holds, last letter 800 ms, 250 ms transitions.",
        "parameters": {
            "timing": "constant",
            "source": "simulated",
            "hold_ms": 243,
            "last_hold_ms": 800,
            "transition_ms": 250,
        },
    },
    {
        "key": "normalized",
        "label": "Normalized constant",
        "description": "Constant timing scaled to the total duration of the built-in "
        "Variable model, {provenance}.",
        "parameters": {"timing": "normalized", "source": "simulated"},
    },
)

OPEN_QUESTIONS = (
    (
        "what-made-you-select",
        "What made you select an animation as most similar to actual fingerspelling?",
    ),
    ("words-identified", "Which words were you able to identify?"),
    (
        "features-easier",
        "If there were certain features that made some clips easier to understand than "
        "others, please describe them.",
    ),
    (
        "features-missing",
        "If there were certain features missing that would have made these animations "
        "better, please describe them.",
    ),
    ("further-comments", "Please write any further comments you have here:"),
)


def _with_provenance(conditions) -> list[dict[str, Any]]:
    """Return *conditions* with the built-in Variable model's training and leave-one-out
    in their descriptions (one source: the model's own metadata)."""
    from synthesis.timing import published_model

    provenance = published_model().provenance()
    return [
        {**c, "description": c["description"].format(provenance=provenance)} for c in conditions
    ]


def fingerspelling_timing_study() -> dict[str, Any]:
    """Return the definition of the 4 conditions × 8 words, 48-comparison study."""
    questions = numbered(
        [
            {
                "key": "age",
                "kind": "choice",
                "text": "What is your age?",
                "options": scale(["18–25", "26–35", "36–45", "46–55", "56–65", "66+"]),
            },
            asl_fluency(),
            {
                "key": "name",
                "kind": "short_text",
                "text": "Your name",
                "required": False,
                "is_personal": True,
            },
            {
                "key": "email",
                "kind": "email",
                "text": "Your e-mail address",
                "required": False,
                "is_personal": True,
            },
            {
                "key": "most-natural",
                "kind": "pairwise",
                "text": (
                    "Which animation is the most similar to actual fingerspelling (most natural)?"
                ),
                "allow_no_difference": False,
            },
            {
                "key": "compare-clips",
                "kind": "comparative",
                "text": "How do the two clips compare?",
                "help_text": "Choose the middle point if you see no difference.",
                "options": scale(
                    [
                        "Clip 1 much more natural",
                        "Clip 1 a little more natural",
                        "They look the same",
                        "Clip 2 a little more natural",
                        "Clip 2 much more natural",
                    ]
                ),
            },
            *(
                {"key": key, "kind": "open", "text": text, "required": False}
                for key, text in OPEN_QUESTIONS
            ),
        ]
    )
    blocks = numbered(
        [
            {"key": "demographics", "kind": "demographics", "title": "About you"},
            {"key": "instructions", "kind": "instructions", "title": "Instructions"},
            {
                "key": "practice",
                "kind": "practice",
                "title": "Practice",
                "intro_text": "A practice page first: its answer is not analysed.",
            },
            {
                "key": "comparisons",
                "kind": "trials",
                "title": "Comparisons",
                "randomize_order": True,
            },
            {"key": "closing", "kind": "closing", "title": "Closing questions"},
        ]
    )
    trials = [
        {
            "key": "demographics",
            "block": "demographics",
            "kind": "demographic",
            "questions": ["age", "asl-fluency", "name", "email"],
        },
        {
            "key": "instructions",
            "block": "instructions",
            "kind": "info",
            "title": "Instructions",
            "text": (
                "On each page, you will see two video clips and will be asked to choose which "
                "clip is most similar to actual fingerspelling by a fluent ASL signer. An "
                "example clip is presented below. Please watch each video, first Clip 1 and "
                "then Clip 2. This study must be completed in one sitting.\n\n"
                "The study will take approximately 15–20 minutes."
            ),
            "item": EXAMPLE_WORD,
            "condition_a": "variable",
        },
        {
            "key": "practice-1",
            "block": "practice",
            "kind": "pairwise",
            "item": EXAMPLE_WORD,
            "condition_a": "variable",
            "condition_b": "constant",
            "questions": ["most-natural"],
        },
    ]
    keys = [condition["key"] for condition in CONDITIONS]
    for index, (word, first, second) in enumerate(balanced_pair_assignment(keys, WORDS), 1):
        trials.append(
            {
                "key": f"cmp-{index:02d}",
                "block": "comparisons",
                "kind": "pairwise",
                "item": word,
                "condition_a": first,
                "condition_b": second,
                "questions": ["most-natural"],
            }
        )
    # An attention check among the comparisons: two identical clips, to be rated the same.
    for number, (word, first, second) in enumerate(attention_checks(keys, WORDS, 1, seed=6), 1):
        trials.append(
            {
                "key": f"attention-{number}",
                "block": "comparisons",
                "kind": "comparative",
                "item": word,
                "condition_a": first,
                "condition_b": second,
                "questions": ["compare-clips"],
                "is_attention_check": True,
                "expected_answer": "3",
            }
        )
    trials.append(
        {
            "key": "closing",
            "block": "closing",
            "kind": "open",
            "questions": [key for key, _ in OPEN_QUESTIONS],
        }
    )
    items = [{"key": word, "kind": "word", "text": word} for word in WORDS]
    items.append({"key": EXAMPLE_WORD, "kind": "word", "text": EXAMPLE_WORD, "is_practice": True})
    return definition(
        {
            "slug": "fingerspelling-timing",
            "title": "ASL fingerspelling timing (demo)",
            "description": (
                "Which fingerspelling animation looks most like a fluent signer? Four timing "
                "models compared on eight words (after Wheatland 2016, ch. 5)."
            ),
            "status": "open",
            "consent_text": (
                "This study shows short animations of ASL fingerspelling and asks which looks "
                "most natural. It takes about 15–20 minutes. Your answers are anonymous; you "
                "may stop at any time. Continuing means you agree to take part."
            ),
            "one_sitting": True,
            "allow_back": True,
            "completion_code": "FSPELL-DEMO",
        },
        conditions=numbered(_with_provenance(CONDITIONS)),
        items=numbered(items),
        questions=questions,
        blocks=blocks,
        trials=numbered(trials),
    )
