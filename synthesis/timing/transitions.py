"""Transition times from pose distance: ``t = a + b · d(from, to)`` (seed 000 §4.2.2).

The distance is taken over the hand model's joint angles (radians) between the two
letters' poses: RMSD (seed 000's choice: r = 0.44), Manhattan (r = 0.42) or Chebyshev
(r = 0.38). All three are symmetric, so A→B and B→A take the same time.
"""

from dataclasses import dataclass

import numpy as np
from scipy import stats

from synthesis.fingerspelling.alphabet import letter_pose

METRICS = ("rmsd", "manhattan", "chebyshev")


def pose_distance(a_rad: np.ndarray, b_rad: np.ndarray, metric: str = "rmsd") -> np.ndarray:
    """Return the distance between DOF vectors (..., n_dofs), radians."""
    difference = np.asarray(a_rad) - np.asarray(b_rad)
    if metric == "rmsd":
        return np.sqrt(np.mean(difference**2, axis=-1))
    if metric == "manhattan":
        return np.sum(np.abs(difference), axis=-1)
    if metric == "chebyshev":
        return np.max(np.abs(difference), axis=-1)
    raise ValueError(f"Unknown distance {metric!r}; use one of {', '.join(METRICS)}.")


def letter_distance(first: str, second: str, metric: str = "rmsd") -> float:
    """Return the distance between two letters' poses (radians).

    Right-hand poses (a mirror image changes no distance); J and Z by their base poses.
    """
    return float(pose_distance(letter_pose(first), letter_pose(second), metric))


@dataclass(frozen=True)
class TransitionModel:
    """A fitted line: intercept (ms), slope (ms per radian), its metric and fit statistics."""

    intercept_ms: float
    slope_ms_per_rad: float
    metric: str = "rmsd"
    r: float = float("nan")
    mean_abs_error_ms: float = float("nan")
    nobs: int = 0
    minimum_ms: float = 1000.0 / 120.0

    @classmethod
    def fit(
        cls, distances_rad: np.ndarray, times_ms: np.ndarray, metric: str = "rmsd"
    ) -> "TransitionModel":
        """Fit by least squares (scipy.stats.linregress) to measured transitions."""
        distances = np.asarray(distances_rad, dtype=float)
        times = np.asarray(times_ms, dtype=float)
        if distances.shape != times.shape or distances.size < 3:
            raise ValueError("Fitting transitions needs at least 3 (distance, time) pairs.")
        fit = stats.linregress(distances, times)
        predicted = fit.intercept + fit.slope * distances
        return cls(
            float(fit.intercept),
            float(fit.slope),
            metric,
            float(fit.rvalue),
            float(np.abs(predicted - times).mean()),
            int(distances.size),
        )

    def predict_ms(self, first: str, second: str) -> float:
        """Return the transition time (ms) from one letter to the next, at least one frame."""
        distance = letter_distance(first, second, self.metric)
        return max(self.intercept_ms + self.slope_ms_per_rad * distance, self.minimum_ms)

    def to_dict(self) -> dict:
        return {
            "intercept_ms": self.intercept_ms,
            "slope_ms_per_rad": self.slope_ms_per_rad,
            "metric": self.metric,
            "r": self.r,
            "mean_abs_error_ms": self.mean_abs_error_ms,
            "nobs": self.nobs,
            "minimum_ms": self.minimum_ms,
        }

    @classmethod
    def from_dict(cls, data: dict) -> "TransitionModel":
        if data.get("metric", "rmsd") not in METRICS:
            raise ValueError(f"Unknown distance {data.get('metric')!r} in a transition model.")
        return cls(**{k: data[k] for k in data if k in cls.__dataclass_fields__})
