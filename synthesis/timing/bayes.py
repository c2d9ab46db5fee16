"""The naïve Bayes hold classifier of the Variable model (seed 000 §4.2.1).

Classes are hold durations from 8.33 ms to 333.33 ms in 8.33 ms steps (one frame at
120 fps); features are categorical (:mod:`synthesis.timing.features`);
``P(C_k | d) ∝ P(C_k) · Π_i P(d_i | C_k)`` (seed 000 eq. 4.3) with Laplace smoothing.
A feature value never seen in training (a new word) is left out of the product rather
than counted as a zero, as seed 000 uses the word only when it is known.
"""

from dataclasses import dataclass

import numpy as np

from synthesis.timing.features import DEFAULT_FEATURES, FEATURES

CLASS_STEP_MS = 1000.0 / 120.0
N_CLASSES = 40  # 8.33 … 333.33 ms
CLASSES_MS = CLASS_STEP_MS * np.arange(1, N_CLASSES + 1)


def hold_class(hold_ms: float) -> int:
    """Return the class index (0-based) of a hold duration: the nearest 8.33 ms step."""
    return int(np.clip(round(hold_ms / CLASS_STEP_MS), 1, N_CLASSES)) - 1


@dataclass(frozen=True)
class LeaveOneOut:
    """Leave-one-out evaluation: accuracy (exact class), mean |error| and mean signed error."""

    accuracy: float
    mean_abs_error_ms: float
    mean_signed_error_ms: float
    nobs: int

    def to_dict(self) -> dict:
        return {
            "accuracy": self.accuracy,
            "mean_abs_error_ms": self.mean_abs_error_ms,
            "mean_signed_error_ms": self.mean_signed_error_ms,
            "nobs": self.nobs,
        }


@dataclass(frozen=True, eq=False)
class HoldClassifier:
    """Counts per class, and per feature value and class, from training holds.

    Probabilities are Laplace-smoothed with *alpha* (prior and likelihoods alike).
    """

    features: tuple[str, ...]
    class_counts: np.ndarray
    value_counts: dict[str, dict[str, np.ndarray]]
    alpha: float = 1.0

    @classmethod
    def fit(
        cls,
        samples: list[tuple[dict[str, str], float]],
        features: tuple[str, ...] = DEFAULT_FEATURES,
        alpha: float = 1.0,
    ) -> "HoldClassifier":
        """Count (features, hold_ms) samples into a classifier."""
        unknown = [f for f in features if f not in FEATURES]
        if unknown:
            raise ValueError(f"Unknown feature(s): {', '.join(unknown)}.")
        if not samples:
            raise ValueError("A hold classifier needs at least one training hold.")
        class_counts = np.zeros(N_CLASSES)
        value_counts: dict[str, dict[str, np.ndarray]] = {f: {} for f in features}
        for values, hold_ms in samples:
            k = hold_class(hold_ms)
            class_counts[k] += 1
            for feature in features:
                counts = value_counts[feature].setdefault(values[feature], np.zeros(N_CLASSES))
                counts[k] += 1
        return cls(tuple(features), class_counts, value_counts, alpha)

    def log_posterior(self, values: dict[str, str], leave_out: int | None = None) -> np.ndarray:
        """Return unnormalised log P(C_k | d) for every class (N_CLASSES,).

        *leave_out* removes one training hold of that class with these very values,
        which is leave-one-out evaluation without refitting.
        """
        class_counts = self.class_counts.copy()
        if leave_out is not None:
            class_counts[leave_out] -= 1
        total = class_counts.sum()
        # Laplace smoothing (α) in the prior as in the likelihoods: a class no training
        # hold fell in is unlikely, not impossible (issue 38).
        log_p = np.log((class_counts + self.alpha) / (total + self.alpha * N_CLASSES))
        for feature in self.features:
            table = self.value_counts[feature]
            counts = table.get(values[feature])
            if counts is None:
                continue  # never seen: no evidence either way
            counts = counts.copy()
            if leave_out is not None:
                counts[leave_out] -= 1
                if counts.sum() <= 0:
                    continue  # the left-out hold was its only example
            n_values = len(table)
            log_p += np.log((counts + self.alpha) / (class_counts + self.alpha * n_values))
        return log_p

    def predict_ms(self, values: dict[str, str]) -> float:
        """Return the most probable hold duration (ms) for one letter's features."""
        return float(CLASSES_MS[int(np.argmax(self.log_posterior(values)))])

    def leave_one_out_predictions(
        self, samples: list[tuple[dict[str, str], float]]
    ) -> tuple[np.ndarray, np.ndarray]:
        """Return per sample whether its hold class was predicted and the predicted hold
        (ms), each sample classified by the model without it."""
        hits, predicted = [], []
        for values, hold_ms in samples:
            k = hold_class(hold_ms)
            guess = int(np.argmax(self.log_posterior(values, leave_out=k)))
            hits.append(guess == k)
            predicted.append(CLASSES_MS[guess])
        return np.array(hits, dtype=bool), np.array(predicted, dtype=float)

    def leave_one_out(self, samples: list[tuple[dict[str, str], float]]) -> LeaveOneOut:
        """Evaluate on the training samples, each classified by a model without it."""
        hits, predicted = self.leave_one_out_predictions(samples)
        error = predicted - np.array([hold_ms for _, hold_ms in samples])
        return LeaveOneOut(
            accuracy=int(hits.sum()) / len(samples),
            mean_abs_error_ms=float(np.abs(error).mean()),
            mean_signed_error_ms=float(error.mean()),
            nobs=len(samples),
        )

    def to_dict(self) -> dict:
        """Return the counts as plain, readable data."""
        return {
            "features": list(self.features),
            "alpha": self.alpha,
            "class_ms": [round(float(v), 3) for v in CLASSES_MS],
            "class_counts": self.class_counts.astype(int).tolist(),
            "value_counts": {
                feature: {value: counts.astype(int).tolist() for value, counts in table.items()}
                for feature, table in self.value_counts.items()
            },
        }

    @classmethod
    def from_dict(cls, data: dict) -> "HoldClassifier":
        """Read counts written by :meth:`to_dict`."""
        return cls(
            tuple(data["features"]),
            np.asarray(data["class_counts"], dtype=float),
            {
                feature: {value: np.asarray(c, dtype=float) for value, c in table.items()}
                for feature, table in data["value_counts"].items()
            },
            float(data.get("alpha", 1.0)),
        )
