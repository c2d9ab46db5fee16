"""The hold classifier's accuracy by feature and by training-set size (seed 000 Figs 4.4–4.6).

Fig. 4.4 adds the ten features of Table 4.2 one at a time, in the table's order, and
evaluates each classifier by leave-one-out; Fig. 4.5 does the same without the letter's
shape (the seed dropped it: 72.37 % → 75.00 %); Fig. 4.6 trains on a random 30, 50 and
80 % of the holds (91, 152 and 243 of 304) and evaluates again. The seed prints a few of
its figures' values (:data:`PUBLISHED_POINTS`); the rest it only plotted. Error bars are
the standard error of the mean, as the seed's: of the per-hold hits and absolute errors,
and across *repeats* random subsets for Fig. 4.6.
"""

from dataclasses import dataclass

import numpy as np

from synthesis.timing.bayes import HoldClassifier
from synthesis.timing.features import DEFAULT_FEATURES, FEATURES

Sample = tuple[dict[str, str], float]
# What seed 000 §4.2.1 states of its figures (the rest is only plotted).
PUBLISHED_POINTS = {
    ("all ten", 9): 60.53,  # accuracy (%) with features 1–9, before the word is added
    ("all ten", 10): 72.37,  # with all ten
    ("without shape", 9): 75.00,  # the nine kept
}
SHARES = (0.3, 0.5, 0.8, 1.0)


@dataclass(frozen=True)
class CurvePoint:
    """One classifier's leave-one-out: accuracy and mean |error| with their s.e."""

    curve: str
    step: int
    label: str
    holds: int
    accuracy: float
    accuracy_se: float
    mean_error_ms: float
    mean_error_se: float

    def to_dict(self) -> dict:
        published = PUBLISHED_POINTS.get((self.curve, self.step))
        return {
            "curve": self.curve,
            "step": self.step,
            "label": self.label,
            "holds": self.holds,
            "accuracy_pct": round(100 * self.accuracy, 2),
            "accuracy_se_pct": round(100 * self.accuracy_se, 2),
            "mean_error_ms": round(self.mean_error_ms, 2),
            "mean_error_se_ms": round(self.mean_error_se, 2),
            "published_accuracy_pct": "" if published is None else published,
        }


def leave_one_out_errors(
    samples: list[Sample], features: tuple[str, ...]
) -> tuple[np.ndarray, np.ndarray]:
    """Return per hold whether its class was hit (1.0 or 0.0) and its absolute error (ms),
    by the classifier's own leave-one-out."""
    hits, predicted = HoldClassifier.fit(samples, features).leave_one_out_predictions(samples)
    return hits.astype(float), np.abs(predicted - np.array([hold for _, hold in samples]))


def _se(values: np.ndarray) -> float:
    return float(values.std(ddof=1) / np.sqrt(len(values))) if len(values) > 1 else 0.0


def feature_curve(samples: list[Sample], curve: str = "all ten") -> list[CurvePoint]:
    """Return Fig. 4.4 (*curve* ``"all ten"``) or Fig. 4.5 (``"without shape"``): the
    leave-one-out after adding each feature of Table 4.2 in order."""
    order = FEATURES if curve == "all ten" else DEFAULT_FEATURES
    points = []
    for step in range(1, len(order) + 1):
        hits, errors = leave_one_out_errors(samples, order[:step])
        points.append(
            CurvePoint(
                curve,
                step,
                f"+ {order[step - 1]}",
                len(samples),
                float(hits.mean()),
                _se(hits),
                float(errors.mean()),
                _se(errors),
            )
        )
    return points


def size_curve(
    samples: list[Sample], rng: np.random.Generator, repeats: int = 20, shares=SHARES
) -> list[CurvePoint]:
    """Return Fig. 4.6: the leave-one-out of the nine-feature classifier on a random
    share of the holds, mean and s.e. over *repeats* draws (one draw at the full set)."""
    points = []
    for step, share in enumerate(shares, start=1):
        count = round(share * len(samples))
        draws = 1 if count == len(samples) else repeats
        accuracy, error = [], []
        for _ in range(draws):
            subset = [samples[i] for i in rng.choice(len(samples), count, replace=False)]
            hits, errors = leave_one_out_errors(subset, DEFAULT_FEATURES)
            accuracy.append(hits.mean())
            error.append(errors.mean())
        accuracy, error = np.array(accuracy), np.array(error)
        points.append(
            CurvePoint(
                "training size",
                step,
                f"{100 * share:.0f} %",
                count,
                float(accuracy.mean()),
                _se(accuracy),
                float(error.mean()),
                _se(error),
            )
        )
    return points


def plot_curves(points: list[CurvePoint], path, title: str):
    """Draw Figs 4.4–4.6 side by side: accuracy and mean error with s.e. bars."""
    from synthesis.plotting import pyplot

    plt = pyplot()
    curves = list(dict.fromkeys(p.curve for p in points))
    figure, axes = plt.subplots(2, len(curves), figsize=(4 * len(curves), 5.5), squeeze=False)
    for column, curve in enumerate(curves):
        chosen = [p for p in points if p.curve == curve]
        steps = [p.step for p in chosen]
        axes[0, column].errorbar(
            steps,
            [100 * p.accuracy for p in chosen],
            [100 * p.accuracy_se for p in chosen],
            marker="o",
            capsize=3,
        )
        published = [(s, v) for (c, s), v in PUBLISHED_POINTS.items() if c == curve]
        if published:
            axes[0, column].plot(
                *zip(*published, strict=True),
                "s",
                color="#d62728",
                label="seed 000 (stated in the text)",
            )
            axes[0, column].legend(fontsize=7)
        axes[1, column].errorbar(
            steps,
            [p.mean_error_ms for p in chosen],
            [p.mean_error_se for p in chosen],
            marker="o",
            capsize=3,
        )
        axes[0, column].set_title(curve, fontsize=9)
        axes[1, column].set_xticks(steps, [p.label for p in chosen], rotation=60, fontsize=7)
        axes[0, column].set_xticks(steps, [])
    axes[0, 0].set_ylabel("accuracy (%)")
    axes[1, 0].set_ylabel("mean error (ms)")
    figure.suptitle(title, fontsize=8)
    figure.tight_layout()
    figure.savefig(path, dpi=110)
    plt.close(figure)
    return path
