"""The ASL manual alphabet, a word's timing, and a word spelled as a hand motion."""

from synthesis.fingerspelling.alphabet import AlphabetError, letter_pose
from synthesis.fingerspelling.spelling import simple_timing, spell, word_letters
from synthesis.fingerspelling.word_timing import TimingError, WordTiming

__all__ = [
    "AlphabetError",
    "TimingError",
    "WordTiming",
    "letter_pose",
    "simple_timing",
    "spell",
    "word_letters",
]
