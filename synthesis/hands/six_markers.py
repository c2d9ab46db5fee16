"""Compare three six-marker sets rebuilt by LWR, as seed 000 Figs 3.3–3.5 do.

Seed 000 §3.2.3 compares its PCA-ranked six markers (Alg. 2) with the cluster-pose
search's six (Alg. 1) and with the manual set Hoyet et al. (I3D 2012) proposed from
perception studies, all rebuilt by its own LWR reconstruction ("not a fair assessment"
of Hoyet's IK-based method, the seed notes, but a control for the choice of markers).
Hoyet et al. recommend markers on the five fingertips, two on the palm and one on the
thumb's base; of the 13-marker set the seed (and this project) uses, that leaves the
five fingertips and a palm marker (the index MCP): :data:`HOYET_SIX`, this project's
reading, which has no marker on the middle joints, the weakness the seed's Fig. 3.4
names. Errors: the mean marker distance (cm, Table 3.1's measure) and the mean joint
angle error over the reconstructed DOFs (degrees, Fig. 3.5's measure), per frame and
overall.
"""

import textwrap
from dataclasses import dataclass

import numpy as np

from synthesis.hands.markers import MARKERS, rank_markers, search_marker_sets, virtual_markers
from synthesis.hands.posedb import reconstructed_columns
from synthesis.hands.reconstruct import (
    LwrModel,
    PoseDatabase,
    marker_error_cm,
    reconstruct_lwr,
)

HOYET_SIX = ("thumb_tip", "index_mcp", "index_tip", "middle_tip", "ring_tip", "pinky_tip")
METHODS = ("PCA influence (Alg. 2)", "cluster pose (Alg. 1)", "manual (Hoyet et al. 2012)")


@dataclass(frozen=True)
class SixMarkerSet:
    """One six-marker set, how it was chosen, and its reconstruction's errors."""

    method: str
    markers: tuple[str, ...]
    marker_error_cm: float
    angle_error_deg: float
    angle_error_per_frame_deg: np.ndarray

    def to_dict(self) -> dict:
        return {
            "method": self.method,
            "set": " ".join(self.markers),
            "marker_error_cm": round(self.marker_error_cm, 3),
            "angle_error_deg": round(self.angle_error_deg, 3),
        }


def six_marker_sets(
    database: PoseDatabase,
    hand,
    test_dofs_rad: np.ndarray,
    rate_hz: float,
    rng: np.random.Generator,
    poses: int = 200,
) -> list[SixMarkerSet]:
    """Return the three sets of :data:`METHODS`, each rebuilt from *test_dofs_rad* by LWR
    over *database* (Alg. 1 searches a *poses*-pose clustering, as Table 3.1 does)."""
    truth = virtual_markers(hand, test_dofs_rad, database.root)
    alg2 = tuple(sorted(int(i) for i in rank_markers(database.markers)[0][:6]))
    alg1 = search_marker_sets(6, database.clustered(poses, rng).markers, truth)[0][0]
    manual = tuple(sorted(MARKERS.index(name) for name in HOYET_SIX))
    columns = reconstructed_columns(hand, database.root)
    found = []
    for method, chosen in zip(METHODS, (alg2, alg1, manual), strict=True):
        model = LwrModel.fit(database, chosen, variance=1.0)
        rebuilt = np.array(test_dofs_rad, dtype=float)
        rebuilt[:, columns] = reconstruct_lwr(truth[:, list(chosen)], model, rate_hz)[:, columns]
        rebuilt = hand.clip(rebuilt)
        error_cm, _ = marker_error_cm(truth, virtual_markers(hand, rebuilt, database.root))
        difference = np.abs(rebuilt[:, columns] - test_dofs_rad[:, columns])
        per_frame = np.degrees(difference.mean(axis=1))
        names = tuple(MARKERS[i] for i in chosen)
        found.append(SixMarkerSet(method, names, error_cm, float(per_frame.mean()), per_frame))
    return found


def plot_six_marker_sets(found: list[SixMarkerSet], rate_hz: float, path, title: str):
    """Draw each set's joint angle error per frame (seed 000 Fig. 3.5); return *path*."""
    from synthesis.plotting import pyplot

    plt = pyplot()
    figure, axis = plt.subplots(figsize=(8, 3.2))
    for entry in found:
        times = np.arange(len(entry.angle_error_per_frame_deg)) / rate_hz
        label = f"{entry.method}: {entry.angle_error_deg:.2f}° mean"
        axis.plot(times, entry.angle_error_per_frame_deg, label=label, linewidth=1.2)
    axis.set_xlabel("time (s)")
    axis.set_ylabel("mean digit angle error (°)")
    axis.set_title(textwrap.fill(title, 110), fontsize=8)
    axis.legend(fontsize=8)
    figure.tight_layout()
    figure.savefig(path, dpi=110)
    plt.close(figure)
    return path
