"""Reconstruct the full hand from a few markers (seed 000 §3.1 and §3.2).

- **LWR** (§3.2.2): joint angles go through PCA; for each frame of the sparse markers,
  every database sample is weighted by the inverse Euclidean distance of its sparse
  markers to the query's, a weighted linear regression from sparse markers to the
  principal components is fitted, and the prediction is taken. The components'
  trajectories are smoothed with a 17-sample cone filter (at 120 Hz) before becoming
  joint angles again. The regression maps to every component by default
  (``LWR_VARIANCE = 1.0``), as §3.2.4 found best ("the full 54 components"); a smaller
  share of the variance keeps fewer. With every component kept, LWR through PCA *is*
  the direct weighted regression onto the joint angles (a linear map of the outputs
  commutes with weighted least squares and with the filter), so §3.2.4's finding that
  PCA beats direct regression cannot show here: keeping fewer components only adds
  error (HEAVEN from 3 markers: 0.767 cm with all 23, 0.782 cm with the 15 that hold
  99.9 %, 0.864 cm with 10 at 99 %).
- **Nearest pose** (§3.1): the database is clustered by k-means into p poses
  (p = 50…1000), each frame takes the pose whose sparse markers are nearest (summed
  distance), and a 15-sample cone filter smooths the result. The seed smoothed the
  markers and fitted the hand to them; the poses here carry their joint angles, so the
  angles are smoothed.

Filter widths scale with the frame rate (17 and 15 samples are at 120 Hz).
"""

import zipfile
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from scipy.cluster.vq import kmeans2
from scipy.ndimage import convolve1d

from synthesis.hands.markers import check_root, marker_distances, pca

LWR_FILTER_SAMPLES = 17
NEAREST_FILTER_SAMPLES = 15
FILTER_RATE_HZ = 120.0
LWR_VARIANCE = 1.0


def cone_kernel(samples: int) -> np.ndarray:
    """Return the cone (triangular) filter of *samples* taps: weights h + 1 − |k|, summing to 1."""
    if samples < 1 or samples % 2 == 0:
        raise ValueError(f"A cone filter has an odd number of taps, not {samples}.")
    half = samples // 2
    weights = half + 1 - np.abs(np.arange(-half, half + 1))
    return weights / weights.sum()


def filter_samples(samples_at_120: int, rate_hz: float) -> int:
    """Return the odd tap count that spans the same time at *rate_hz* as at 120 Hz."""
    taps = round(samples_at_120 * rate_hz / FILTER_RATE_HZ)
    return max(1, taps if taps % 2 else taps + 1)


def cone_filter(values: np.ndarray, samples: int) -> np.ndarray:
    """Return *values* (n_frames, …) smoothed over time by a cone filter (ends repeated)."""
    return convolve1d(np.asarray(values, float), cone_kernel(samples), axis=0, mode="nearest")


def lwr_weights(query: np.ndarray, samples: np.ndarray) -> np.ndarray:
    """Return the inverse Euclidean distance from *query* (d,) to each sample (n, d)."""
    distance = np.linalg.norm(np.asarray(samples, float) - np.asarray(query, float), axis=1)
    return 1.0 / np.maximum(distance, 1e-9)


def kmeans_plus_plus(samples: np.ndarray, count: int, rng: np.random.Generator) -> np.ndarray:
    """Return up to *count* initial centres chosen by k-means++ (Arthur and Vassilvitskii).

    scipy's own ``minit="++"`` takes about 45 s for 1,000 centres of 3,000 poses; keeping
    each sample's distance to its nearest centre up to date takes well under a second.
    Stops early when every sample coincides with a centre (fewer distinct poses).
    """
    samples = np.asarray(samples, float)
    chosen = [int(rng.integers(len(samples)))]
    nearest = np.sum((samples - samples[chosen[0]]) ** 2, axis=1)
    while len(chosen) < count and nearest.sum() > 0:
        pick = int(rng.choice(len(samples), p=nearest / nearest.sum()))
        chosen.append(pick)
        nearest = np.minimum(nearest, np.sum((samples - samples[pick]) ** 2, axis=1))
    return samples[chosen]


@dataclass(frozen=True, eq=False)
class PoseDatabase:
    """Hand poses to reconstruct from: joint angles (n, d) rad, their 13 markers (n, 13, 3) m.

    *source* says what the poses are (every report repeats it); *root* is the link the
    markers are expressed in (``synthesis.hands.markers.ROOTS``).
    """

    dofs_rad: np.ndarray
    markers: np.ndarray
    source: str
    root: str = "wrist"

    def __post_init__(self) -> None:
        check_root(self.root)

    def write(self, path) -> Path:
        """Write the database as ``.npz`` (angles, markers, source) at *path*."""
        path = Path(path)
        with path.open("wb") as handle:
            np.savez(
                handle,
                dofs_rad=self.dofs_rad,
                markers=self.markers,
                source=np.array(self.source),
                root=np.array(self.root),
            )
        return path

    @classmethod
    def read(cls, path) -> "PoseDatabase":
        """Return the database at *path*; raise ValueError naming what is wrong with it."""
        try:
            with np.load(path, allow_pickle=False) as stored:
                dofs, markers = stored["dofs_rad"], stored["markers"]
                source = str(stored["source"])
                root = str(stored["root"]) if "root" in stored else "wrist"
        except (OSError, KeyError, ValueError, zipfile.BadZipFile) as error:
            raise ValueError(
                f"{path}: not a pose database (python -m synthesis.hands "
                f"database writes one): {error}"
            ) from None
        if markers.ndim != 3 or markers.shape[1:] != (13, 3) or len(dofs) != len(markers):
            raise ValueError(f"{path}: a pose database holds 13 markers per pose.")
        if len(dofs) < 2 or not (np.all(np.isfinite(dofs)) and np.all(np.isfinite(markers))):
            raise ValueError(f"{path}: a pose database needs at least 2 finite poses.")
        try:
            return cls(dofs, markers, source, root)
        except ValueError as error:
            raise ValueError(f"{path}: {error}") from None

    def clustered(self, poses: int, rng: np.random.Generator) -> "PoseDatabase":
        """Return *poses* representative poses by k-means over the full marker set (§3.1.2):
        from each cluster, the member nearest its centre."""
        flat = self.markers.reshape(len(self.markers), -1)
        centres, labels = kmeans2(flat, kmeans_plus_plus(flat, poses, rng), minit="matrix")
        poses = len(centres)
        chosen = []
        for k in range(poses):
            members = np.flatnonzero(labels == k)
            if members.size:
                nearest = np.argmin(np.linalg.norm(flat[members] - centres[k], axis=1))
                chosen.append(members[nearest])
        chosen = np.array(sorted(chosen))
        return PoseDatabase(
            self.dofs_rad[chosen],
            self.markers[chosen],
            f"{self.source}, k-means to {len(chosen)} poses",
            self.root,
        )


def reconstruct_nearest(
    sparse: np.ndarray, marker_set, database: PoseDatabase, rate_hz: float
) -> np.ndarray:
    """Return joint angles (n_frames, d) from sparse markers by nearest database pose."""
    distances = marker_distances(sparse, database.markers[:, list(marker_set)]).sum(axis=0)
    chosen = np.argmin(distances, axis=1)
    return cone_filter(database.dofs_rad[chosen], filter_samples(NEAREST_FILTER_SAMPLES, rate_hz))


@dataclass(frozen=True, eq=False)
class LwrModel:
    """The LWR reconstruction's fixed parts: the database's sparse markers and PCA."""

    inputs: np.ndarray  # (n, 3m)
    components: np.ndarray  # (n, k) principal-component scores
    mean: np.ndarray  # (d,)
    basis: np.ndarray  # (d, k)
    neighbours: int

    @classmethod
    def fit(
        cls,
        database: PoseDatabase,
        marker_set,
        variance: float = LWR_VARIANCE,
        neighbours: int = 64,
    ) -> "LwrModel":
        """Return the model over *database* for *marker_set*: PCA keeps the fewest
        components that hold *variance* of the variance (1.0: every one with any)."""
        if not 0 < variance <= 1:
            raise ValueError(f"The share of variance kept is in (0, 1], not {variance}.")
        mean, values, vectors = pca(database.dofs_rad)
        share = np.cumsum(values) / max(values.sum(), 1e-300)
        present = int(np.count_nonzero(values > values[0] * 1e-12)) if len(values) else 0
        keep = min(int(np.searchsorted(share, variance - 1e-12) + 1), max(present, 1))
        basis = vectors[:, :keep]
        inputs = database.markers[:, list(marker_set)].reshape(len(database.markers), -1)
        return cls(inputs, (database.dofs_rad - mean) @ basis, mean, basis, neighbours)

    def predict(self, sparse: np.ndarray) -> np.ndarray:
        """Return the principal components (n_frames, k) of each frame of sparse markers.

        Each frame's regression uses its *neighbours* nearest samples (the rest weigh
        little under inverse-distance weights and only cost time), weighted by inverse
        distance, with an intercept and a small ridge for stability.
        """
        queries = np.asarray(sparse, float).reshape(len(sparse), -1)
        out = np.empty((len(queries), self.components.shape[1]))
        count = min(self.neighbours, len(self.inputs))
        ridge = 1e-6 * np.eye(self.inputs.shape[1] + 1)
        for f, query in enumerate(queries):
            distance = np.linalg.norm(self.inputs - query, axis=1)
            near = np.argpartition(distance, count - 1)[:count]
            w = lwr_weights(query, self.inputs[near])
            x = np.hstack([np.ones((count, 1)), self.inputs[near] - query])
            xw = x * w[:, None]
            beta = np.linalg.solve(x.T @ xw + ridge * w.sum(), xw.T @ self.components[near])
            out[f] = beta[0]  # the fit at the query itself (inputs centred on it)
        return out

    def to_angles(self, components: np.ndarray) -> np.ndarray:
        """Return joint angles (n, d) from principal components (n, k)."""
        return self.mean + components @ self.basis.T


def reconstruct_lwr(sparse: np.ndarray, model: LwrModel, rate_hz: float) -> np.ndarray:
    """Return joint angles (n_frames, d) from sparse markers: LWR, cone-filtered PCs (§3.2.2)."""
    components = cone_filter(model.predict(sparse), filter_samples(LWR_FILTER_SAMPLES, rate_hz))
    return model.to_angles(components)


def marker_error_cm(reference: np.ndarray, reconstructed: np.ndarray) -> tuple[float, float]:
    """Return the mean and s.d. over frames of the average marker distance, cm (Table 3.1)."""
    per_frame = np.linalg.norm(np.asarray(reference) - np.asarray(reconstructed), axis=-1)
    per_frame = per_frame.mean(axis=1) * 100
    return float(per_frame.mean()), float(per_frame.std())
