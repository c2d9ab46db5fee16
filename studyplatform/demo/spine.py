"""Define the automated spine study of seed 003 §5 (spec 03 "The study")."""

from typing import Any

from studyplatform.demo.common import definition, likert5, numbered, scale
from synthesis.signing.stories import SPINE_STORY

# The story glossed with its non-manual signals (the engine's copy).
SENTENCES = SPINE_STORY

# Seed 003 Table 2 (back translation of the ASL questions and their scale ends).
RATINGS = (
    ("clarity", "Rate the clarity of the sentence.", "Very confusing", "Very clear"),
    (
        "grammaticality",
        "How grammatical was the sentence?",
        "Full of errors, unacceptable",
        "Perfectly correct",
    ),
    ("understandability", "How understandable was the sentence?", "Very hard", "Very easy"),
    ("naturalness", "How natural was the motion?", "Robotic", "Very human-like"),
)


def spine_study() -> dict[str, Any]:
    """Return the definition of the 5 sentences × spine on/off study (ratings + preference).

    Its prompts' ASL videos are signed by the avatar when the demo is rendered
    (:mod:`studyplatform.demo.signed`).
    """
    questions = [
        {
            "key": "hearing-status",
            "kind": "choice",
            "text": "Are you deaf, hard of hearing or hearing?",
            "options": scale(["Deaf", "Hard of hearing", "Hearing"]),
        },
        {
            "key": "preferred-language",
            "kind": "choice",
            "text": "Which language do you prefer?",
            "options": scale(["ASL", "Pidgin Signed English (PSE)"]),
        },
        {
            "key": "years-asl",
            "kind": "number",
            "text": "How many years have you used ASL?",
            "min_value": 0,
            "max_value": 100,
        },
        {
            "key": "born-deaf",
            "kind": "choice",
            "text": "Were you born deaf?",
            "options": scale(["Yes", "No"]),
        },
        *(
            {"key": key, "kind": "likert", "text": text, "options": likert5(low, high)}
            for key, text, low, high in RATINGS
        ),
        {"key": "preferred", "kind": "pairwise", "text": "Which animation do you prefer?"},
        {
            "key": "comments",
            "kind": "open",
            "text": "Is there anything else you noticed about the signing?",
            "help_text": "Type your answer, or sign it with your camera.",
            "required": False,
            "allow_signed_answer": True,
        },
    ]
    blocks = numbered(
        [
            {"key": "pretest", "kind": "demographics", "title": "About you"},
            {
                "key": "ratings",
                "kind": "trials",
                "title": "Part 1: rate each sentence",
                "intro_text": "Each sentence is shown twice, in different versions. Watch "
                "it, then answer the four questions about it.",
                "randomize_order": True,
            },
            {
                "key": "preference",
                "kind": "trials",
                "title": "Part 2: which do you prefer?",
                "randomize_order": True,
            },
            {"key": "closing", "kind": "closing", "title": "Last question"},
        ]
    )
    trials = [
        {
            "key": "pretest",
            "block": "pretest",
            "kind": "demographic",
            "questions": ["hearing-status", "preferred-language", "years-asl", "born-deaf"],
        }
    ]
    # Seed 003 rated the spine-on sentences only; rated in both conditions (in random
    # order), the ratings can compare them, which is the question the demo asks.
    for number in range(1, len(SENTENCES) + 1):
        for condition, suffix in (("spine-on", ""), ("spine-off", "-off")):
            trials.append(
                {
                    "key": f"rate-s{number}{suffix}",
                    "block": "ratings",
                    "kind": "rating",
                    "item": f"S{number}",
                    "condition_a": condition,
                    "questions": [key for key, *_ in RATINGS],
                }
            )
    for number in range(1, len(SENTENCES) + 1):
        # Alternate sides in the design; participants' positions are randomized on top.
        first, second = ("spine-off", "spine-on") if number % 2 else ("spine-on", "spine-off")
        trials.append(
            {
                "key": f"prefer-s{number}",
                "block": "preference",
                "kind": "pairwise",
                "item": f"S{number}",
                "condition_a": first,
                "condition_b": second,
                "questions": ["preferred"],
            }
        )
    trials.append(
        {"key": "comments", "block": "closing", "kind": "open", "questions": ["comments"]}
    )
    return definition(
        {
            "slug": "spine-motion",
            "title": "Automated spine motion in ASL sentences (demo)",
            "description": (
                "A five-sentence story signed with and without automated spine and shoulder "
                "motion (after McDonald et al., SignQUOTE study). Part 1 rates both "
                "versions (the paper rated the spine-on version only); Part 2 compares "
                "them side by side. The prompts' ASL videos are avatar-signed demo "
                "material."
            ),
            "status": "open",
            "asl_first": True,
            "consent_text": (
                "This study shows a short signed story and asks how clear and natural it "
                "looks. Continuing means you agree to take part."
            ),
            "completion_code": "SPINE-DEMO",
        },
        conditions=numbered(
            [
                {
                    "key": "spine-on",
                    "label": "Spine on",
                    "description": "Automated spine and shoulder motion with staggered onsets.",
                    # 30 fps like seed 003's animations (and half the rendering time).
                    "parameters": {"spine": True, "rate_hz": 30.0},
                },
                {
                    "key": "spine-off",
                    "label": "Spine off (control)",
                    "description": "Identical except for the automated spine/shoulder motion.",
                    "parameters": {"spine": False, "rate_hz": 30.0},
                },
            ]
        ),
        items=numbered(
            [
                {"key": f"S{number}", "kind": "sentence", "text": text}
                for number, text in enumerate(SENTENCES, 1)
            ]
        ),
        questions=numbered(questions),
        blocks=blocks,
        trials=numbered(trials),
    )
