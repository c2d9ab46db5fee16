"""Hand-over: a clip's digits rebuilt from a few of its own markers (seed 000 ch. 3).

The clip's hand motion is reduced to its sparse markers (the best m by PCA influence,
Alg. 2) and the digits are reconstructed from them by LWR or the nearest k-means pose,
from a pose database: the engine's alphabet (built once, kept on disk) unless another
is given. The forearm and wrist keep their angles, unless the database's markers are
rooted at the forearm (seed 000's configuration): then the wrist is rebuilt too.
"""

from functools import cache
from pathlib import Path

import numpy as np

from synthesis.diskcache import cached
from synthesis.hands.markers import rank_markers, virtual_markers
from synthesis.hands.posedb import engine_pose_database, reconstructed_columns
from synthesis.hands.reconstruct import (
    LWR_VARIANCE,
    LwrModel,
    PoseDatabase,
    reconstruct_lwr,
    reconstruct_nearest,
)
from synthesis.rigs.body import BodyModel
from synthesis.rigs.hand import HandModel

METHODS = ("lwr", "nearest")
NEAREST_POSES = 1000


def builtin_pose_database(side: str) -> PoseDatabase:
    """Return the engine's alphabet pose database for *side*, from the disk cache when kept."""

    def encode(database: PoseDatabase) -> dict[str, np.ndarray]:
        return {
            "dofs": database.dofs_rad,
            "markers": database.markers,
            "source": np.array(database.source),
        }

    def decode(arrays: dict[str, np.ndarray]) -> PoseDatabase:
        return PoseDatabase(arrays["dofs"], arrays["markers"], str(arrays["source"]), "wrist")

    return cached(
        f"hand-poses-{side}", ("numpy", "scipy"), lambda: engine_pose_database(side), encode, decode
    )


def pose_database(side: str, path: str = "") -> PoseDatabase:
    """Return the pose database at *path* (a file from ``python -m synthesis.hands
    database``), or the built-in one for *side* when empty."""
    return PoseDatabase.read(path) if path else builtin_pose_database(side)


@cache
def _prepared(
    side: str,
    markers: int,
    method: str,
    path: str = "",
    version: int = 0,
    variance: float = LWR_VARIANCE,
):
    database = pose_database(side, path)
    chosen = tuple(int(i) for i in rank_markers(database.markers)[0][:markers])
    if method == "lwr":
        return chosen, database.root, LwrModel.fit(database, chosen, variance)
    return chosen, database.root, database.clustered(NEAREST_POSES, np.random.default_rng(0))


def _version(path: str) -> int:
    """Return the file's modification time (ns): a changed database is read again."""
    try:
        return Path(path).stat().st_mtime_ns if path else 0
    except OSError as error:
        raise ValueError(f"{path}: cannot be read ({error}).") from None


def reconstruct_hand(
    hand_dofs_rad: np.ndarray,
    side: str,
    rate_hz: float,
    markers: int = 3,
    method: str = "lwr",
    database: str = "",
    variance: float = LWR_VARIANCE,
) -> np.ndarray:
    """Return hand-model DOFs (n, 30) with the digits (and, from a forearm-rooted database,
    the wrist) rebuilt from *markers* of their markers."""
    if method not in METHODS:
        raise ValueError(f"method must be one of {', '.join(METHODS)}, not {method!r}.")
    hand = HandModel(side)
    dofs = np.asarray(hand_dofs_rad, dtype=float)
    chosen, root, model = _prepared(side, markers, method, database, _version(database), variance)
    sparse = virtual_markers(hand, dofs, root)[:, list(chosen)]
    if method == "lwr":
        rebuilt = reconstruct_lwr(sparse, model, rate_hz)
    else:
        rebuilt = reconstruct_nearest(sparse, chosen, model, rate_hz)
    columns = reconstructed_columns(hand, root)
    out = dofs.copy()
    out[:, columns] = rebuilt[:, columns]
    return hand.clip(out)


def reconstruct_motion(
    rig,
    dofs_rad: np.ndarray,
    rate_hz: float,
    markers: int = 3,
    method: str = "lwr",
    database: str = "",
    variance: float = LWR_VARIANCE,
) -> np.ndarray:
    """Return a hand's or the body's DOFs with every hand's digits reconstructed."""
    if isinstance(rig, HandModel):
        return reconstruct_hand(dofs_rad, rig.side, rate_hz, markers, method, database, variance)
    if not isinstance(rig, BodyModel):
        raise ValueError("Reconstruction needs the engine's hand or body.")
    out = np.asarray(dofs_rad, dtype=float)
    for side in ("right", "left"):
        where = rig.hand_dofs(side)
        hand = np.tile(HandModel(side).neutral(), (len(out), 1))
        hand[:, where >= 0] = out[:, where[where >= 0]]
        rebuilt = reconstruct_hand(hand, side, rate_hz, markers, method, database, variance)
        out = rig.with_hand(out, side, rebuilt)
    return out
