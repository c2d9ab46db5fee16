"""Score typed answers against the target words (spec 07 "Intelligibility")."""

import difflib
import re
import unicodedata

import numpy as np
import pandas as pd

from analysis.conditions import SCORE_COLUMNS
from analysis.summaries import IntelligibilityScore
from analysis.tidy import analysed

# Fingerspelled words are glossed letter by letter (T-O-Y, Ç-A-Y); both spellings mean one
# word. Letters and digits of any script count ([^\W_]): ÇAY is not AY.
_SPELLED = re.compile(r"\b(?:[^\W\d_]-){1,}[^\W\d_]\b")
_WORD = re.compile(r"(?:[^\W_]|['’])+")
# Upper-casing is not Turkish-aware (i → I, not İ): dotted and dotless capitals match.
_TURKISH_I = str.maketrans({"İ": "I"})
FUZZY_RATIO = 0.8
FUZZY_MIN_LETTERS = 5


def words(text: str) -> list[str]:
    """Split a gloss or an answer into upper-case words ("T-O-Y car!" → ["TOY", "CAR"]),
    letters of any script kept ("çay" → ["ÇAY"]), Unicode-normalised (NFC)."""
    text = unicodedata.normalize("NFC", text)
    joined = _SPELLED.sub(lambda match: match.group(0).replace("-", ""), text)
    found = _WORD.findall(joined.replace("-", " "))
    return [word.upper().translate(_TURKISH_I).replace("’", "'") for word in found]


def word_accuracy(answer: str, target: str, fuzzy: bool = True) -> float:
    """Return the fraction of target words found in the answer, each answer word used once.

    With *fuzzy*, a misspelling within difflib ratio ≥ 0.8 counts ("ELEFANT" for
    "ELEPHANT") in target words of :data:`FUZZY_MIN_LETTERS` or more letters: in shorter
    ones one letter makes another word (AY, moon, for ÇAY, tea; CAT for CAR).
    """
    wanted = words(target)
    if not wanted:
        return float("nan")
    given = words(answer)
    found = 0
    for word in wanted:
        if word in given:
            given.remove(word)
            found += 1
        elif fuzzy and len(word) >= FUZZY_MIN_LETTERS:
            close = difflib.get_close_matches(word, given, n=1, cutoff=FUZZY_RATIO)
            if close:
                given.remove(close[0])
                found += 1
    return found / len(wanted)


def accuracy_scores(frame: pd.DataFrame, fuzzy: bool = True) -> pd.DataFrame:
    """Return each scored answer's accuracy as a long score table (measure "accuracy").

    Text rows with a ``target`` are scored; open answers without one are not.
    """
    columns = list(SCORE_COLUMNS)
    if "target" not in frame.columns:
        return pd.DataFrame(columns=columns)
    rows = frame[frame["kind"].eq("text") & frame["target"].ne("") & analysed(frame)]
    accuracy = [
        word_accuracy(answer, target, fuzzy)
        for answer, target in zip(rows["text"], rows["target"], strict=True)
    ]
    return pd.DataFrame(
        {
            "measure": "accuracy",
            "participant": rows["participant"].to_numpy(),
            "item": rows["item"].to_numpy(),
            "condition": rows["condition_a"].to_numpy(),
            "score": np.asarray(accuracy, float),
        },
        columns=columns,
    )


def score_intelligibility(
    frame: pd.DataFrame, fuzzy: bool = True
) -> tuple[IntelligibilityScore, ...]:
    """Average the answers' accuracy (:func:`accuracy_scores`) per condition × item."""
    scored = accuracy_scores(frame, fuzzy)
    result = []
    for (condition, item), group in scored.groupby(["condition", "item"], sort=True):
        values = group["score"].dropna()
        n = len(values)
        result.append(
            IntelligibilityScore(
                condition=condition,
                item=item,
                n=n,
                mean_accuracy=float(values.mean()) if n else float("nan"),
                sem=float(values.std(ddof=1) / np.sqrt(n)) if n > 1 else float("nan"),
            )
        )
    return tuple(result)
