"""Manual alphabets (ASL, Libras) as data, a word's timing, and a word spelled as a hand
motion."""

from synthesis.fingerspelling.alphabet import AlphabetError, letter_pose, two_handed_letter
from synthesis.fingerspelling.alphabets import (
    DEFAULT_ALPHABET,
    ManualAlphabet,
    alphabet_codes,
    manual_alphabet,
)
from synthesis.fingerspelling.fist_letters import FIST_LETTERS, ThumbPlace, fist_letter, thumb_place
from synthesis.fingerspelling.spelling import simple_timing, spell, word_letters
from synthesis.fingerspelling.word_timing import TimingError, WordTiming

__all__ = [
    "DEFAULT_ALPHABET",
    "FIST_LETTERS",
    "AlphabetError",
    "ManualAlphabet",
    "ThumbPlace",
    "TimingError",
    "WordTiming",
    "alphabet_codes",
    "fist_letter",
    "letter_pose",
    "manual_alphabet",
    "simple_timing",
    "spell",
    "thumb_place",
    "two_handed_letter",
    "word_letters",
]
