"""How a fingerspelled word is timed: a hold per letter and a transition per letter pair.

Every condition of the fingerspelling study (spec 02) comes down to this: the Motion
capture recording's own timing, the Variable model's predictions, Huenerfauth's Constant
timing and its Normalized version. Times are milliseconds, as seed 000 reports them.
"""

from dataclasses import dataclass, field

import numpy as np

from synthesis.formats import check_header

FORMAT = "signstudy.word-timing"
FORMAT_VERSION = 1


class TimingError(ValueError):
    """A timing that does not fit its word, or a malformed timing file."""


@dataclass(frozen=True)
class WordTiming:
    """Holds (n,) and transitions (n − 1,) in ms for the *n* letters of a word.

    *condition* names where the timing came from ("constant", "variable", …);
    *metadata* says how (model parameters, source of published statistics, …).
    """

    letters: tuple[str, ...]
    hold_ms: tuple[float, ...]
    transition_ms: tuple[float, ...]
    condition: str = "custom"
    metadata: dict = field(default_factory=dict, compare=False)

    def __post_init__(self) -> None:
        letters = tuple(str(c).upper() for c in self.letters)
        holds = tuple(float(v) for v in self.hold_ms)
        transitions = tuple(float(v) for v in self.transition_ms)
        if not letters:
            raise TimingError("A word timing needs at least one letter.")
        n = len(letters)
        if len(holds) != n:
            raise TimingError(f"{n} letters need {n} holds, not {len(holds)}.")
        if len(transitions) != n - 1:
            raise TimingError(f"{n} letters need {n - 1} transitions, not {len(transitions)}.")
        values = np.array(holds + transitions)
        if not np.all(np.isfinite(values)) or np.any(values <= 0):
            raise TimingError("Holds and transitions must be positive numbers of milliseconds.")
        object.__setattr__(self, "letters", letters)
        object.__setattr__(self, "hold_ms", holds)
        object.__setattr__(self, "transition_ms", transitions)

    @property
    def word(self) -> str:
        return "".join(self.letters)

    @property
    def total_ms(self) -> float:
        """Return the word's duration: first hold's start to the last hold's end."""
        return float(sum(self.hold_ms) + sum(self.transition_ms))

    def hold_starts_ms(self) -> np.ndarray:
        """Return when each letter's hold begins, ms from the first hold's start."""
        starts = np.zeros(len(self.letters))
        for k in range(1, len(self.letters)):
            starts[k] = starts[k - 1] + self.hold_ms[k - 1] + self.transition_ms[k - 1]
        return starts

    def scaled(self, factor: float, condition: str | None = None) -> "WordTiming":
        """Return the timing with every hold and transition multiplied by *factor*."""
        if not factor > 0:
            raise TimingError(f"A time scale must be positive, not {factor!r}.")
        return WordTiming(
            self.letters,
            tuple(v * factor for v in self.hold_ms),
            tuple(v * factor for v in self.transition_ms),
            condition or self.condition,
            {**self.metadata, "scale": factor},
        )

    def to_dict(self) -> dict:
        """Return the timing as plain JSON-ready data (a versioned, readable format)."""
        return {
            "format": FORMAT,
            "version": FORMAT_VERSION,
            "word": self.word,
            "condition": self.condition,
            "hold_ms": [round(v, 3) for v in self.hold_ms],
            "transition_ms": [round(v, 3) for v in self.transition_ms],
            "total_ms": round(self.total_ms, 3),
            "metadata": self.metadata,
        }

    @classmethod
    def from_dict(cls, data: dict) -> "WordTiming":
        """Read a timing written by :meth:`to_dict`; TimingError names what is wrong."""
        check_header(data, FORMAT, FORMAT_VERSION, "word timing", TimingError)
        try:
            return cls(
                tuple(data["word"]),
                tuple(data["hold_ms"]),
                tuple(data["transition_ms"]),
                data.get("condition", "custom"),
                dict(data.get("metadata") or {}),
            )
        except KeyError as error:
            raise TimingError(f"A word timing lacks {error.args[0]!r}.") from None
