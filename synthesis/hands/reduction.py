"""Reduce a hand motion's DOFs by irrelevance and redundancy (seed 002 §4; spec 05).

Curves are rotation angles in degrees, one value per frame (the seed works at 30 fps).

- *Irrelevance*: a curve whose range is below a threshold becomes its mean.
- *Redundancy*: every curve is standardised (mean 0, s.d. 1); for curves a and b,
  ``rmsd1 = sqrt(mean((a − b)²))`` measures a positive linear relation and
  ``rmsd2 = sqrt(mean((a + b)²))`` a negative one. Below a threshold, the curve with the
  smaller standard deviation is rebuilt from the one with the larger:
  ``a = (b − mean b)/std b · std a + mean a`` (positive) or
  ``a = (mean b − b)/std b · std a + mean a`` (negative), keeping a's mean and s.d.
- *Chains* resolve to the root controller: if b is built from c, a is built from c
  (the seed's §5.2), with the sign composed along the chain.

Pairs are taken from the closest relation up; a curve is rebuilt from at most one
controller, and a pair that would close a loop is skipped.
"""

from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np


@dataclass(frozen=True)
class Relation:
    """A dependent curve rebuilt from its (root) controlling curve.

    *sign* +1 for a positive relation (rmsd1), −1 for a negative one (rmsd2); *rmsd* the
    standardised distance between the dependent curve and its root controller under
    that sign; *pair_rmsd* the distance of the pair that made the relation.
    """

    dependent: str
    controller: str
    sign: int
    rmsd: float
    pair_rmsd: float

    @property
    def metric(self) -> str:
        return "rmsd1" if self.sign > 0 else "rmsd2"


@dataclass(frozen=True)
class Reduction:
    """Which curves a reduction replaces: by their mean (*constant*) or from another."""

    names: tuple[str, ...]
    range_deg: float
    rmsd: float
    constant: dict[str, float] = field(default_factory=dict)
    ranges_deg: dict[str, float] = field(default_factory=dict)
    relations: tuple[Relation, ...] = ()

    @property
    def dof_count(self) -> int:
        """Return how many curves remain free (neither constant nor rebuilt)."""
        return len(self.names) - len(self.constant) - len(self.relations)

    @property
    def free(self) -> tuple[str, ...]:
        """Return the curves that remain free, in order."""
        dependent = {r.dependent for r in self.relations}
        return tuple(n for n in self.names if n not in self.constant and n not in dependent)


def standardise(curves: np.ndarray) -> np.ndarray:
    """Return each column at mean 0 and s.d. 1 (a constant column stays 0)."""
    curves = np.asarray(curves, dtype=float)
    std = curves.std(axis=0)
    return (curves - curves.mean(axis=0)) / np.where(std > 0, std, 1.0)


def rmsd_matrices(curves: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Return rmsd1 and rmsd2 between every pair of standardised curves (n_curves, n_curves).

    For standardised curves, mean((a ∓ b)²) = 2 ∓ 2·mean(a·b): one matrix product gives
    every pair (seed 002 §4.1, 1225 pairs for 50 curves).
    """
    z = standardise(curves)
    n = len(z)
    products = z.T @ z / n
    squares = np.mean(z**2, axis=0)
    total = squares[:, None] + squares[None, :]
    rmsd1 = np.sqrt(np.clip(total - 2 * products, 0, None))
    rmsd2 = np.sqrt(np.clip(total + 2 * products, 0, None))
    return rmsd1, rmsd2


def rebuild(dependent: np.ndarray, controller: np.ndarray, sign: int) -> np.ndarray:
    """Return *dependent* rebuilt from *controller* (seed 002 §4.2), same mean and s.d.

    Positive: ``(b − mean b)/std b · std a + mean a``; negative: ``(mean b − b)/std b ·
    std a + mean a``.
    """
    a, b = np.asarray(dependent, float), np.asarray(controller, float)
    std_b = b.std()
    if std_b == 0:
        return np.full_like(a, a.mean())
    return sign * (b - b.mean()) / std_b * a.std() + a.mean()


def find_reduction(
    curves_deg: np.ndarray, names: Sequence[str], range_deg: float = 1.0, rmsd: float | None = 0.3
) -> Reduction:
    """Return which curves (n_frames, n_curves; degrees) become constant or dependent.

    *range_deg*: curves moving less than this become their mean; *rmsd*: pairs closer
    than this (either metric) are related (None: irrelevance only).
    """
    curves = np.asarray(curves_deg, dtype=float)
    names = tuple(names)
    if curves.ndim != 2 or curves.shape[1] != len(names):
        raise ValueError(f"curves must be (frames, {len(names)}), not {curves.shape}.")
    if len(curves) < 2:
        raise ValueError("A reduction needs at least 2 frames.")
    ranges = np.ptp(curves, axis=0)
    constant = {names[i]: float(curves[:, i].mean()) for i in np.flatnonzero(ranges < range_deg)}
    relations: list[Relation] = []
    if rmsd is not None:
        relations = _relations(curves, names, ranges >= range_deg, rmsd)
    return Reduction(
        names,
        range_deg,
        rmsd if rmsd is not None else float("nan"),
        constant,
        {n: float(r) for n, r in zip(names, ranges, strict=True)},
        tuple(relations),
    )


def _relations(curves, names, relevant, threshold) -> list[Relation]:
    rmsd1, rmsd2 = rmsd_matrices(curves)
    std = curves.std(axis=0)
    candidates = []
    for i, j in zip(*np.triu_indices(len(names), 1), strict=True):
        if not (relevant[i] and relevant[j]):
            continue
        for sign, metric in ((1, rmsd1[i, j]), (-1, rmsd2[i, j])):
            if metric < threshold:
                candidates.append((float(metric), int(i), int(j), sign))
    # parent[k] = (root, sign): k is rebuilt from root with that composed sign.
    parent: dict[int, tuple[int, int, float]] = {}

    def root(k: int) -> tuple[int, int]:
        sign = 1
        while k in parent:
            k, s, _ = parent[k]
            sign *= s
        return k, sign

    for metric, i, j, sign in sorted(candidates):
        dependent, controller = (i, j) if std[i] < std[j] else (j, i)
        if dependent in parent:
            continue
        top, top_sign = root(controller)
        if top == dependent:
            continue  # would close a loop
        parent[dependent] = (top, sign * top_sign, metric)
        # Curves that hung from the new dependent now hang from its root.
        for k, (r, s, m) in list(parent.items()):
            if r == dependent:
                parent[k] = (top, s * sign * top_sign, m)
    z = standardise(curves)
    relations = []
    for k, (r, s, m) in sorted(parent.items()):
        distance = float(np.sqrt(np.mean((z[:, k] - s * z[:, r]) ** 2)))
        relations.append(Relation(names[k], names[r], s, distance, m))
    return relations


def apply_reduction(curves_deg: np.ndarray, reduction: Reduction) -> np.ndarray:
    """Return the curves with the reduction applied: constants and rebuilt curves."""
    curves = np.array(curves_deg, dtype=float)
    index = {name: i for i, name in enumerate(reduction.names)}
    original = curves.copy()
    for name, mean in reduction.constant.items():
        curves[:, index[name]] = mean
    for relation in reduction.relations:
        k, r = index[relation.dependent], index[relation.controller]
        curves[:, k] = rebuild(original[:, k], original[:, r], relation.sign)
    return curves


def reconstruction_error_deg(original: np.ndarray, reduced: np.ndarray) -> np.ndarray:
    """Return the RMS error per curve (degrees) between the original and reduced curves."""
    difference = np.asarray(original, float) - np.asarray(reduced, float)
    return np.sqrt(np.mean(difference**2, axis=0))


SEED_STEPS = ((1.0, None), (1.0, 0.3), (5.0, None), (5.0, 0.5))


def dof_counts(
    curves_deg: np.ndarray, names: Sequence[str], steps=SEED_STEPS
) -> list[tuple[float, float | None, int]]:
    """Return the free DOFs after each of seed 002's four steps (Table 5)."""
    return [(r, m, find_reduction(curves_deg, names, r, m).dof_count) for r, m in steps]
