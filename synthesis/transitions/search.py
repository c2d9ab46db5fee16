"""Find the stored transition whose surroundings best match a gap (seed 001 §3.5, §5.2.4).

The seed compares descriptors by (weighted) Euclidean distance. Its §5.2.4 notes that
the k = 0 coefficients, sums of ten angles, dwarf the others, and proposes z-scoring
each column over the database, and comparing in a PCA-reduced space. All three are
offered (:data:`WEIGHTINGS`); evaluation leaves the query's own transition out.
"""

from collections.abc import Collection
from dataclasses import dataclass

import numpy as np

from synthesis.transitions.database import TransitionDatabase

WEIGHTINGS = ("raw", "zscore", "pca")
# PCA keeps the components that explain this share of the z-scored variance.
PCA_VARIANCE = 0.95


@dataclass(frozen=True, eq=False)
class DescriptorSearch:
    """Nearest-descriptor search over a database's entries.

    *weighting*: ``raw`` (the seed's Euclidean distance, Eq. 3.6, with column *weights*
    w_i), ``zscore`` (each column to mean 0 and s.d. 1 over the database) or ``pca``
    (z-scored, then projected onto the components explaining 95 % of the variance).
    Seed 001 does not print its w_i (it only says they normalize the DCT terms): unit
    weights, the default here, are an assumption, not the seed's values.
    """

    database: TransitionDatabase
    weighting: str = "zscore"
    weights: np.ndarray | None = None

    def __post_init__(self) -> None:
        if self.weighting not in WEIGHTINGS:
            raise ValueError(
                f"weighting must be one of {', '.join(WEIGHTINGS)}, not {self.weighting!r}."
            )
        raw = self.database.descriptors()
        weights = np.ones(raw.shape[1]) if self.weights is None else np.asarray(self.weights)
        if weights.shape != (raw.shape[1],) or np.any(weights < 0):
            raise ValueError(f"weights must be {raw.shape[1]} non-negative numbers.")
        mean = raw.mean(axis=0) if self.weighting != "raw" else np.zeros(raw.shape[1])
        scale = raw.std(axis=0) if self.weighting != "raw" else np.ones(raw.shape[1])
        scale = np.where(scale > 1e-12, scale, 1.0) / np.sqrt(weights + 1e-300)
        projection = np.eye(raw.shape[1])
        if self.weighting == "pca":
            _, singular, vt = np.linalg.svd((raw - mean) / scale, full_matrices=False)
            share = np.cumsum(singular**2) / np.sum(singular**2)
            keep = int(np.searchsorted(share, PCA_VARIANCE) + 1)
            projection = vt[:keep].T
        object.__setattr__(self, "_mean", mean)
        object.__setattr__(self, "_scale", scale)
        object.__setattr__(self, "_projection", projection)
        object.__setattr__(self, "_space", self.transform(raw))
        object.__setattr__(self, "_ids", np.array([e.id for e in self.database.entries]))

    def transform(self, descriptors: np.ndarray) -> np.ndarray:
        """Return descriptors (…, 42) in the search's space."""
        return ((np.asarray(descriptors, float) - self._mean) / self._scale) @ self._projection

    def distances(self, descriptor: np.ndarray) -> np.ndarray:
        """Return the distance from *descriptor* (42,) to every entry (n_entries,)."""
        return np.linalg.norm(self._space - self.transform(descriptor), axis=1)

    def nearest(self, descriptor: np.ndarray, exclude: Collection[str] = ()) -> int:
        """Return the index of the entry nearest *descriptor*, never one of *exclude* (ids)."""
        distances = self.distances(descriptor)
        if exclude:
            distances = np.where(np.isin(self._ids, list(exclude)), np.inf, distances)
        if not np.isfinite(distances).any():
            raise LookupError("Every transition of the database is excluded.")
        return int(np.argmin(distances))
