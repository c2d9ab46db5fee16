"""Score typed answers against the target words (spec 07 "Intelligibility")."""

import difflib
import re

import numpy as np
import pandas as pd

from analysis.results import IntelligibilityScore
from analysis.tidy import analysed

# Fingerspelled words are glossed letter by letter (T-O-Y); both spellings mean one word.
_SPELLED = re.compile(r"\b(?:[A-Za-z]-){1,}[A-Za-z]\b")
_WORD = re.compile(r"[A-Za-z0-9']+")
FUZZY_RATIO = 0.8


def words(text: str) -> list[str]:
    """Split a gloss or an answer into upper-case words ("T-O-Y car!" → ["TOY", "CAR"])."""
    joined = _SPELLED.sub(lambda match: match.group(0).replace("-", ""), text)
    return [word.upper() for word in _WORD.findall(joined.replace("-", " "))]


def word_accuracy(answer: str, target: str, fuzzy: bool = True) -> float:
    """Return the fraction of target words found in the answer, each answer word used once.

    With *fuzzy*, a misspelling within difflib ratio ≥ 0.8 counts ("ELEFANT" for
    "ELEPHANT").
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
        elif fuzzy:
            close = difflib.get_close_matches(word, given, n=1, cutoff=FUZZY_RATIO)
            if close:
                given.remove(close[0])
                found += 1
    return found / len(wanted)


def score_intelligibility(
    frame: pd.DataFrame, fuzzy: bool = True
) -> tuple[IntelligibilityScore, ...]:
    """Score text rows that have a target and average per condition × item.

    The target is the ``target`` column when the table has one, else nothing: open
    answers without a target are not scored.
    """
    if "target" not in frame.columns:
        return ()
    rows = frame[frame["kind"].eq("text") & frame["target"].ne("") & analysed(frame)]
    if rows.empty:
        return ()
    accuracy = [
        word_accuracy(answer, target, fuzzy)
        for answer, target in zip(rows["text"], rows["target"], strict=True)
    ]
    scored = rows.assign(accuracy=accuracy)
    result = []
    for (condition, item), group in scored.groupby(["condition_a", "item"], sort=True):
        values = group["accuracy"].dropna()
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
