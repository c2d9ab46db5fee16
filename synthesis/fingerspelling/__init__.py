"""The ASL manual alphabet, a word's timing, and a word spelled as a hand motion."""

from synthesis.fingerspelling.alphabet import AlphabetError, letter_pose
from synthesis.fingerspelling.fist_letters import FIST_LETTERS, ThumbPlace, fist_letter, thumb_place
from synthesis.fingerspelling.spelling import simple_timing, spell, word_letters
from synthesis.fingerspelling.word_timing import TimingError, WordTiming

__all__ = [
    "FIST_LETTERS",
    "AlphabetError",
    "ThumbPlace",
    "TimingError",
    "WordTiming",
    "fist_letter",
    "letter_pose",
    "simple_timing",
    "spell",
    "thumb_place",
    "word_letters",
]
