"""The features of a letter in a word that predict how long it is held (seed 000 Table 4.2).

1 the letter; 2 the number of letters in the word; 3 the previous letter; 4 the following
letter; 5 the place in the word (first, middle, last); 6 the letter's index; 7 vowel or
consonant; 8 part of a double letter; 9 the letter's shape (open, closed, intermediate);
10 the word itself. Seed 000 §4.2.1 dropped the shape (it lowered accuracy) and uses the
word only when it was in the training data; those are the defaults here too.
"""

FEATURES = (
    "letter",
    "word_length",
    "previous",
    "following",
    "place",
    "index",
    "vowel",
    "double",
    "shape",
    "word",
)
DEFAULT_FEATURES = tuple(f for f in FEATURES if f != "shape")
VOWELS = frozenset("AEIOU")
# The project's grouping of handshapes: fingers extended, curled shut, or in between.
SHAPES = {
    **dict.fromkeys("BFHKLPRUVWY", "open"),
    **dict.fromkeys("AEMNOST", "closed"),
    **dict.fromkeys("CDGIJQXZ", "intermediate"),
}
# Values outside the sentence: the letter before the first, after the last.
EDGE = "#"


def letter_features(word: str, index: int) -> dict[str, str]:
    """Return all ten features of the letter at *index* of *word*, as strings."""
    letters = word.upper()
    n = len(letters)
    if not 0 <= index < n:
        raise IndexError(f"{word!r} has no letter {index}.")
    letter = letters[index]
    previous = letters[index - 1] if index else EDGE
    following = letters[index + 1] if index + 1 < n else EDGE
    place = "first" if index == 0 else "last" if index == n - 1 else "middle"
    return {
        "letter": letter,
        "word_length": str(n),
        "previous": previous,
        "following": following,
        "place": place,
        "index": str(index),
        "vowel": "vowel" if letter in VOWELS else "consonant",
        "double": "double" if letter in (previous, following) else "single",
        "shape": SHAPES.get(letter, "intermediate"),
        "word": letters,
    }


def word_features(word: str) -> list[dict[str, str]]:
    """Return the features of every letter of *word*."""
    return [letter_features(word, k) for k in range(len(word))]
