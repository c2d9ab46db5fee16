"""Hand dimensionality (spec 05): fewer DOFs by irrelevance and redundancy (seed 002).

:mod:`~synthesis.hands.reduction` finds which curves of a hand motion are irrelevant
(barely moving) or redundant (a linear function of another) and rebuilds them.
"""

from synthesis.hands.reduction import (
    SEED_STEPS,
    Reduction,
    Relation,
    apply_reduction,
    dof_counts,
    find_reduction,
    rebuild,
    reconstruction_error_deg,
    rmsd_matrices,
    standardise,
)

__all__ = [
    "SEED_STEPS",
    "Reduction",
    "Relation",
    "apply_reduction",
    "dof_counts",
    "find_reduction",
    "rebuild",
    "reconstruction_error_deg",
    "rmsd_matrices",
    "standardise",
]
