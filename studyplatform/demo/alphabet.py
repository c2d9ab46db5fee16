"""Define the Alphabet legibility study: engine letters against human-captured letters.

Participants see one letter per page on the same hand avatar and type which letter it
is (scored automatically). Each letter comes twice: formed by the engine's alphabet, and
as a real signer's recording (the spoken-to-signed package's ASL lexicon, fitted to the
hand: :func:`attach_human_letters`). The recordings have no depth, so the second source
is the fitter's reading of them (issue 52: MediaPipe reads 1 of its 9 clips right), and
the study's texts say so.
"""

from typing import Any

from studyplatform.demo.common import asl_fluency, definition, numbered

SLUG = "alphabet-legibility"
# Letters of distinct families: fist (A, S), flat (B), curved (C, O), pointing (D, L),
# two fingers (V), thumb and pinky (Y).
LETTERS = ("A", "B", "C", "D", "L", "O", "S", "V", "Y")

CONDITIONS = (
    {
        "key": "engine",
        "label": "Engine alphabet",
        "description": "The letter as the engine's hand alphabet forms it.",
        "parameters": {"source": "alphabet", "timing": "constant", "last_hold_ms": 1200},
    },
    {
        "key": "human",
        "label": "Human recording, fitted without depth",
        "description": (
            "A real signer's recording of the letter (spoken-to-signed ASL lexicon), fitted "
            "to the same hand and played as performed. The recordings hold 2-D video "
            "landmarks without depth, so the fit guesses how far each finger bends toward "
            "the camera: A, C, O and S come out wrong in every frame (A with the thumb out, "
            "C flat, O open, S half-curled). This condition measures the fit, not the "
            "signer; do not report it as human handshapes."
        ),
        "parameters": {"source": "recording", "timing": "mocap"},
    },
)


def alphabet_legibility_study() -> dict[str, Any]:
    """Return the definition of the 2 sources × 9 letters identification study."""
    questions = numbered(
        [
            asl_fluency(),
            {
                "key": "which-letter",
                "kind": "intelligibility",
                "text": "Which letter is the hand showing? Type the letter.",
            },
        ]
    )
    blocks = numbered(
        [
            {"key": "about-you", "kind": "demographics", "title": "About you"},
            {
                "key": "letters",
                "kind": "trials",
                "title": "Letters",
                "intro_text": "Each page shows one fingerspelled letter. Type the letter you see.",
                "randomize_order": True,
            },
        ]
    )
    trials = [
        {
            "key": "about-you",
            "block": "about-you",
            "kind": "demographic",
            "questions": ["asl-fluency"],
        }
    ]
    for letter in LETTERS:
        for condition in CONDITIONS:
            trials.append(
                {
                    "key": f"{letter.lower()}-{condition['key']}",
                    "block": "letters",
                    "kind": "intelligibility",
                    "item": letter,
                    "condition_a": condition["key"],
                    "questions": ["which-letter"],
                }
            )
    return definition(
        {
            "slug": SLUG,
            "title": "ASL alphabet legibility (demo)",
            "description": (
                "Can signers read the avatar's letters? The engine's handshapes against "
                "real signers' recordings fitted to the same hand. The recordings have no "
                "depth, so the fitted 'human' letters are the fitter's reading of them, not "
                "the signer's handshapes (see the condition's description)."
            ),
            "status": "open",
            "consent_text": (
                "This study shows short animations of single ASL letters and asks which "
                "letter you see. It takes about 5 minutes. Your answers are anonymous; you "
                "may stop at any time. Continuing means you agree to take part."
            ),
            "completion_code": "ALPHABET-DEMO",
        },
        conditions=numbered(list(CONDITIONS)),
        items=numbered([{"key": letter, "kind": "word", "text": letter} for letter in LETTERS]),
        questions=questions,
        blocks=blocks,
        trials=numbered(trials),
    )


def attach_human_letters(study) -> int:
    """Attach each letter's human recording to the study's items; return how many.

    Raise LexiconMissing when the recordings' package is not installed. Letters that
    already have a recording keep it.
    """
    from django.core.files import File

    from studyplatform.actions import do_attach_recording
    from synthesis.capture.lexicon import human_letter_files

    files = human_letter_files()
    attached = 0
    for item in study.items.filter(recordings__isnull=True):
        path = files.get(item.text.upper())
        if path is None:
            continue
        with open(path, "rb") as handle:
            do_attach_recording(item, File(handle, name=f"{item.key}.pose"))
        attached += 1
    return attached
