"""The Variable timing model: naïve Bayes holds plus pose-distance transitions (seed 000 §4.2).

A saved model is one human-readable JSON file (format ``signstudy.timing-model``, versioned)
holding the classifier's counts, the regression line and metadata that says where the
numbers came from (trained on recordings, or built from published statistics).
"""

import itertools
import json
from dataclasses import dataclass, field
from pathlib import Path

from synthesis.fingerspelling.word_timing import TimingError, WordTiming
from synthesis.formats import check_header
from synthesis.timing.bayes import HoldClassifier
from synthesis.timing.features import word_features
from synthesis.timing.transitions import TransitionModel

FORMAT = "signstudy.timing-model"
FORMAT_VERSION = 1


@dataclass(frozen=True, eq=False)
class VariableModel:
    """Predict a word's timing: a hold per letter, a transition per letter pair."""

    holds: HoldClassifier
    transitions: TransitionModel
    metadata: dict = field(default_factory=dict)

    def timing(self, word: str) -> WordTiming:
        """Return the Variable timing of *word*."""
        letters = "".join(c for c in word.upper() if not c.isspace())
        if not letters:
            raise TimingError("Nothing to time: the word is empty.")
        holds = tuple(self.holds.predict_ms(values) for values in word_features(letters))
        transitions = tuple(
            self.transitions.predict_ms(a, b) for a, b in itertools.pairwise(letters)
        )
        return WordTiming(
            tuple(letters),
            holds,
            transitions,
            "variable",
            {"model": self.metadata.get("name", "variable"), "source": self.metadata.get("source")},
        )

    @property
    def simulated(self) -> bool:
        """Return whether the model was trained on simulated holds, not recordings."""
        return bool(self.metadata.get("simulated", False))

    def provenance(self) -> str:
        """Return what the model was trained on and its leave-one-out, in plain words,
        beside seed 000 §4.2's (75.00 %, 13.82 ms per hold on 304 recorded holds)."""
        m = self.metadata
        trained = m.get("training") or m.get("source") or "an unnamed input"
        words = f"trained on {trained}"
        if self.simulated and "simulated" not in trained:
            words += " (simulated)"
        loo = m.get("leave_one_out")
        if loo:
            words += (
                f"; leave-one-out {100 * loo['accuracy']:.1f} % exact, "
                f"{loo['mean_abs_error_ms']:.1f} ms per hold (seed 000 §4.2: 75.0 %, "
                "13.82 ms on 304 recorded holds)"
            )
        return words

    def to_dict(self) -> dict:
        """Return the whole model as plain data."""
        return {
            "format": FORMAT,
            "version": FORMAT_VERSION,
            "metadata": self.metadata,
            "holds": self.holds.to_dict(),
            "transitions": self.transitions.to_dict(),
        }

    @classmethod
    def from_dict(cls, data: dict) -> "VariableModel":
        """Read a model written by :meth:`to_dict`; TimingError names what is wrong."""
        check_header(data, FORMAT, FORMAT_VERSION, "timing model", TimingError)
        try:
            return cls(
                HoldClassifier.from_dict(data["holds"]),
                TransitionModel.from_dict(data["transitions"]),
                dict(data.get("metadata") or {}),
            )
        except (KeyError, TypeError, ValueError) as error:
            raise TimingError(f"Malformed timing model: {error}") from None

    def write(self, path: str | Path) -> Path:
        """Write the model as indented JSON."""
        path = Path(path)
        path.write_text(json.dumps(self.to_dict(), indent=1) + "\n", encoding="utf-8")
        return path

    @classmethod
    def read(cls, path: str | Path) -> "VariableModel":
        """Read a model file."""
        try:
            data = json.loads(Path(path).read_text(encoding="utf-8"))
        except json.JSONDecodeError as error:
            raise TimingError(f"{path}: not JSON ({error.msg}, line {error.lineno}).") from None
        return cls.from_dict(data)
