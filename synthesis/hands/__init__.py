"""Hand dimensionality (spec 05): fewer DOFs (seed 002), fewer markers (seed 000 ch. 3).

:mod:`~synthesis.hands.reduction` finds which digit curves of a hand motion are
irrelevant (barely moving) or redundant (a linear function of another) and rebuilds
them; :mod:`~synthesis.hands.markers` places 13 virtual markers on the hand and ranks
them (PCA influence, Alg. 2; exhaustive search, Alg. 1);
:mod:`~synthesis.hands.reconstruct` rebuilds joint angles from a few markers (LWR, or
the nearest k-means pose) from a pose database (:mod:`~synthesis.hands.posedb`);
:mod:`~synthesis.hands.handover` applies it to a clip. Hand curves are read and written
by :mod:`~synthesis.hands.motion`; the command line is ``python -m synthesis.hands``.
"""

from synthesis.hands.handover import reconstruct_hand, reconstruct_motion
from synthesis.hands.markers import (
    MARKERS,
    marker_influence,
    rank_markers,
    search_marker_sets,
    virtual_markers,
)
from synthesis.hands.reconstruct import (
    LwrModel,
    PoseDatabase,
    cone_filter,
    cone_kernel,
    lwr_weights,
    marker_error_cm,
    reconstruct_lwr,
    reconstruct_nearest,
)
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
    "MARKERS",
    "SEED_STEPS",
    "LwrModel",
    "PoseDatabase",
    "Reduction",
    "Relation",
    "apply_reduction",
    "cone_filter",
    "cone_kernel",
    "dof_counts",
    "find_reduction",
    "lwr_weights",
    "marker_error_cm",
    "marker_influence",
    "rank_markers",
    "rebuild",
    "reconstruct_hand",
    "reconstruct_lwr",
    "reconstruct_motion",
    "reconstruct_nearest",
    "reconstruction_error_deg",
    "rmsd_matrices",
    "search_marker_sets",
    "standardise",
    "virtual_markers",
]
