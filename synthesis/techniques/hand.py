"""The hand full, simplified or rebuilt from a few markers (spec 05; seeds 002, 000 ch. 3).

``reduced`` finds, on the clip's own motion, the digit curves that barely move (they
become their mean) and those that follow another (rebuilt from it), as seed 002 does at
30 fps, and shows the hand with only the remaining DOFs free. ``reconstructed`` keeps
only the clip's best few markers and rebuilds the digits from them by seed 000's LWR or
nearest k-means pose, from a pose database (the engine's alphabet unless another is
given). The forearm and wrist are left as they are.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from synthesis.techniques.kinds import SIGNED
from synthesis.techniques.parameters import ClipError, Parameter
from synthesis.techniques.registry import MOTION, Technique

if TYPE_CHECKING:
    from synthesis.techniques.request import Build

HANDS = ("full", "reduced", "reconstructed")
LABELS = {
    "full": "full hand",
    "reduced": "reduced DOFs (seed 002)",
    "reconstructed": "reconstructed from sparse markers (seed 000 ch. 3)",
}
METHOD_LABELS = {"lwr": "locally weighted regression", "nearest": "nearest k-means pose"}


def _apply(build: Build) -> Build:
    import numpy as np

    values = build.request.parameters
    if values["hand"] == "full":
        return build
    if not isinstance(build.motion, np.ndarray):
        raise ClipError(
            f"A {values['hand']} hand needs the engine's own DOFs: a retargeted recording "
            "cannot be changed here; use python -m synthesis.hands on it first."
        )
    if values["hand"] == "reconstructed":
        from synthesis.hands.handover import reconstruct_motion

        try:
            dofs = reconstruct_motion(
                build.rig,
                build.motion,
                build.request.rate_hz,
                values["hand_markers"],
                values["hand_method"],
                values["hand_database"],
            )
        except ValueError as error:
            raise ClipError(str(error)) from None
        return build.but(motion=dofs)
    from synthesis.hands.motion import from_dofs, reduce_motion

    motion = from_dofs(build.rig, build.motion, build.request.rate_hz)
    reduced, _ = reduce_motion(motion, values["hand_range_deg"], values["hand_rmsd"])
    return build.but(motion=build.rig.clip(reduced.dofs_rad))


def _summary(values) -> str:
    if values["hand"] == "full":
        return LABELS["full"]
    if values["hand"] == "reconstructed":
        database = values["hand_database"] or "the engine's alphabet"
        return (
            f"{LABELS['reconstructed']}: {values['hand_markers']} markers, "
            f"{METHOD_LABELS[values['hand_method']]}, pose database: {database}"
        )
    return (
        f"{LABELS['reduced']}: curves moving under {values['hand_range_deg']:g}° fixed, "
        f"curves within rmsd {values['hand_rmsd']:g} of another rebuilt from it"
    )


TECHNIQUE = Technique(
    name="hand",
    label="Hand DOFs",
    kinds=SIGNED | {"word"},
    parameters=(
        Parameter(
            "hand",
            "choice",
            "full",
            "full: every DOF of the hand; reduced: the curves seed 002 finds irrelevant "
            "or redundant in this clip's motion are fixed or rebuilt from others; "
            "reconstructed: the digits rebuilt from a few of their markers (seed 000).",
            choices=HANDS,
            labels=LABELS,
        ),
        Parameter(
            "hand_range_deg",
            "float",
            5.0,
            "Reduced: a curve moving less than this becomes its mean (seed 002: 1 or 5).",
            minimum=0,
            maximum=90,
            units="deg",
        ),
        Parameter(
            "hand_rmsd",
            "float",
            0.5,
            "Reduced: curves closer than this (standardised RMS deviation, either sign) "
            "are related (seed 002: 0.3 or 0.5).",
            minimum=0,
            maximum=2,
        ),
        Parameter(
            "hand_markers",
            "int",
            3,
            "Reconstructed: how many markers are kept (the most influential by PCA; "
            "seed 000 used 3 and 6).",
            minimum=1,
            maximum=13,
        ),
        Parameter(
            "hand_method",
            "choice",
            "lwr",
            "Reconstructed: locally weighted regression to principal components "
            "(seed 000 §3.2) or the nearest of 1,000 k-means poses (§3.1).",
            choices=("lwr", "nearest"),
            labels=METHOD_LABELS,
        ),
        Parameter(
            "hand_database",
            "file",
            "",
            "Reconstructed: a pose database (python -m synthesis.hands database: recordings, "
            "words, simulated captures); empty: the engine's alphabet.",
        ),
    ),
    source="seed 002 §4–5; seed 000 ch. 3",
    stage=MOTION,
    order=20,
    apply=_apply,
    summary=_summary,
)
