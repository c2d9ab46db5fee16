"""The GPLVM distance between letters: seed 000 §4.2.2's fourth metric (r = 0.22).

The 26 letter poses (the hand model's DOFs that vary between letters, radians, centred)
are embedded in a two-dimensional latent space by a Gaussian Process Latent Variable
Model (Lawrence 2005; GPy's ``GPLVM``: RBF kernel, latent points initialised by PCA and
optimised with the kernel by L-BFGS). The distance is seed 000's
``GPLVMD(a, b) = Σ (c_a − d_b)² / x``: the squared latent distance over the largest one
between two letters, so it runs from 0 to 1 (the seed: E–Z was 1, the farthest).
The embedding takes about ten seconds and is kept in the engine's disk cache. GPy is
imported only here: without it the metric names the package to install.
"""

import itertools
from functools import cache

import numpy as np

ALPHABET = "ABCDEFGHIJKLMNOPQRSTUVWXYZ"
LATENT_DIMS = 2
MAX_ITERATIONS = 2000


class GplvmMissing(ImportError):
    """GPy, which fits the GPLVM, is not installed."""


def embed(
    poses: np.ndarray, latent_dims: int = LATENT_DIMS, max_iterations: int = MAX_ITERATIONS
) -> np.ndarray:
    """Return the GPLVM's latent points (n, latent_dims) of *poses* (n, d), PCA-initialised."""
    try:
        import GPy
    except ImportError:
        raise GplvmMissing(
            "The GPLVM distance needs GPy: run 'make install' (it installs GPy==1.15.0)."
        ) from None
    poses = np.asarray(poses, dtype=float)
    varying = poses[:, poses.std(axis=0) > 1e-9]
    model = GPy.models.GPLVM(varying - varying.mean(axis=0), latent_dims, init="PCA")
    model.optimize(max_iters=max_iterations)
    return np.array(model.X)


@cache
def letter_latents() -> dict[str, np.ndarray]:
    """Return each letter's latent point (right-hand poses; J and Z by their base poses)."""
    from synthesis.diskcache import cached
    from synthesis.fingerspelling.alphabet import letter_pose

    def compute() -> dict[str, np.ndarray]:
        points = embed(np.array([letter_pose(letter) for letter in ALPHABET]))
        return dict(zip(ALPHABET, points, strict=True))

    return cached("gplvm-letters", ("numpy", "scipy", "GPy", "paramz"), compute, dict, dict)


@cache
def _largest() -> float:
    points = letter_latents()
    return max(
        float(np.sum((points[a] - points[b]) ** 2)) for a, b in itertools.combinations(ALPHABET, 2)
    )


def gplvm_distance(first: str, second: str) -> float:
    """Return GPLVMD between two letters (0 to 1), seed 000 §4.2.2."""
    points = letter_latents()
    return float(np.sum((points[first.upper()] - points[second.upper()]) ** 2)) / _largest()
