"""The pose database reconstructions learn from: the engine's alphabet, or recordings.

Seed 000 §3.2.3's ASL database was two continuous runs of the alphabet by one signer
(2,734 samples at 120 Hz). The engine's stand-in spells the alphabet twice, at two
speeds, at 120 Hz; recordings (BVH of the engine's hand, captured ``.pose``) can be
added. Every report names what the database was: the published errors came from Vicon
captures, the engine's database from its own letters.
"""

from collections.abc import Iterable
from dataclasses import replace
from pathlib import Path

import numpy as np

from synthesis.hands.markers import check_root, virtual_markers
from synthesis.hands.motion import digit_columns, read_hand_motion
from synthesis.hands.reconstruct import PoseDatabase
from synthesis.rigs.hand import HandModel
from synthesis.skeleton.retime import resample_curves

ALPHABET = "ABCDEFGHIJKLMNOPQRSTUVWXYZ"
RATE_HZ = 120.0


def reconstructed_columns(hand: HandModel, root: str = "wrist") -> np.ndarray:
    """Return the DOFs the markers carry from *root*: the digits, and the wrist from the forearm."""
    columns, _ = digit_columns(hand)
    if check_root(root) == "wrist":
        return columns
    wrist = [hand.dof_names.index(name) for name in ("wrist_deviation", "wrist_flexion")]
    return np.concatenate([wrist, columns])


def handshapes(hand: HandModel, dofs_rad: np.ndarray, root: str = "wrist") -> np.ndarray:
    """Return the DOFs with what lies above *root* at rest: the database holds handshapes."""
    columns = reconstructed_columns(hand, root)
    out = np.tile(hand.neutral(), (len(dofs_rad), 1))
    out[:, columns] = np.asarray(dofs_rad)[:, columns]
    return out


def pose_database_of(
    hand: HandModel, dofs_rad: np.ndarray, source: str, root: str = "wrist"
) -> PoseDatabase:
    """Return the poses of *dofs_rad* (hand DOFs at 120 Hz) with their markers from *root*."""
    dofs = handshapes(hand, dofs_rad, root)
    return PoseDatabase(dofs, virtual_markers(hand, dofs, root), source, root)


def engine_pose_database(
    side: str = "right",
    runs: Iterable[float] = (1.0, 1.6),
    words: Iterable[str] = (),
    simulated: int = 0,
    root: str = "wrist",
) -> PoseDatabase:
    """Return the engine's poses: the alphabet and *words* spelled once per speed factor in
    *runs* (1 = the engine's own pace), plus *simulated* simulated captures of each word
    (seed 000 §4.3's stand-in: sampled timing and capture noise), all at 120 Hz."""
    from synthesis.fingerspelling.spelling import simple_timing, spell

    hand = HandModel(side)
    frames, parts = (
        [],
        [
            f"alphabet{' and ' + ', '.join(words) if words else ''} "
            f"spelled at {len(tuple(runs))} speeds"
        ],
    )
    for text in (ALPHABET, *words):
        for factor in runs:
            timing = simple_timing(text)
            slower = replace(
                timing,
                hold_ms=tuple(h * factor for h in timing.hold_ms),
                transition_ms=tuple(t * factor for t in timing.transition_ms),
            )
            frames.append(spell(text, side, RATE_HZ, timing=slower))
    if simulated:
        from synthesis.timing.recordings import Recording

        for word in words:
            for seed in range(simulated):
                capture = Recording.simulate(word, seed, side=side, rate_hz=RATE_HZ)
                frames.append(hand.dofs_from_motion(capture.motion))
        parts.append(f"{simulated} simulated captures of each word")
    frames = np.vstack(frames)
    source = f"the engine's {' and '.join(parts)}, {len(frames)} poses at 120 Hz"
    return pose_database_of(hand, frames, source, root)


def recorded_dofs(paths: Iterable[str | Path], side: str = "right") -> np.ndarray:
    """Return hand recordings' DOFs (engine hand BVH or .pose) one after another at 120 Hz."""
    parts = []
    for path in paths:
        motion = read_hand_motion(path, side)
        if not isinstance(motion.rig, HandModel):
            raise ValueError(f"{path}: a pose database takes hand recordings.")
        parts.append(resample_curves(motion.dofs_rad, motion.rate_hz, RATE_HZ))
    return np.vstack(parts)


def recorded_pose_database(
    paths: Iterable[str | Path], side: str = "right", root: str = "wrist"
) -> PoseDatabase:
    """Return the poses of hand recordings (engine hand BVH or .pose), resampled to 120 Hz."""
    paths = list(paths)
    names = ", ".join(Path(path).name for path in paths)
    return pose_database_of(
        HandModel(side), recorded_dofs(paths, side), f"recordings {names}", root
    )


def combined(*databases: PoseDatabase) -> PoseDatabase:
    """Return the poses of several databases together, their sources joined."""
    roots = {d.root for d in databases}
    if len(roots) > 1:
        raise ValueError(f"Pose databases with different marker roots do not mix: {sorted(roots)}.")
    return PoseDatabase(
        np.vstack([d.dofs_rad for d in databases]),
        np.vstack([d.markers for d in databases]),
        "; ".join(d.source for d in databases),
        roots.pop(),
    )


def human_letter_dofs(side: str = "right", letters: str = "") -> dict[str, np.ndarray]:
    """Return each human letter's hand DOFs at 120 Hz (``spoken-to-signed``'s lexicon):
    *letters* in order (repeats once), or A–Z when empty.

    The hand model is fitted to each letter's ``.pose`` file (about a second a letter)
    once and kept, letter by letter, in the engine's disk cache. Raise LexiconMissing
    without the package and ValueError for a letter it has no recording of.
    """
    from synthesis.capture.lexicon import human_letter_files
    from synthesis.diskcache import cached

    files = human_letter_files()
    wanted = "".join(dict.fromkeys(letters.upper())) or "".join(files)
    missing = sorted(set(wanted) - set(files))
    if missing:
        raise ValueError(f"No human recording of {', '.join(missing)}.")

    def fitted(letter: str) -> np.ndarray:
        motion = read_hand_motion(files[letter], side)
        return resample_curves(motion.dofs_rad, motion.rate_hz, RATE_HZ)

    return {
        letter: cached(
            f"human-letter-{side}-{letter}",
            ("numpy", "scipy"),
            lambda letter=letter: fitted(letter),
            lambda dofs: {"dofs": dofs},
            lambda stored: stored["dofs"],
        )
        for letter in wanted
    }


def human_letter_poses(side: str = "right", letters: str = "") -> np.ndarray:
    """Return the human letters' DOFs at 120 Hz one after another (n_frames, 30)."""
    return np.vstack(list(human_letter_dofs(side, letters).values()))
