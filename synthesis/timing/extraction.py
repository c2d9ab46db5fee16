"""Find the letter holds and transitions in a recording of a fingerspelled word (seed 000 §4.1).

1. The hand's average angular velocity per frame, from joint angles smoothed with a
   Savitzky–Golay filter: holds sit at its minima (the hand slows almost to a stop,
   except after the last letter, where it does stop).
2. Word decomposition: every frame's joint angles as a least-squares mix of the word's
   letter poses, ``J_i ≈ Σ_k w_ik L_k`` via the pseudo-inverse (seed 000 eqs. 4.1–4.2);
   a letter's weight peaks where it is formed.
3. Each letter gets an anchor frame, in order, where its weight is high and the velocity
   low (dynamic programming over the frames keeps the order). J and Z get two: where
   their path starts and where it ends.
4. Boundaries: the hand arrives at a hold and leaves it at rest, so around each anchor
   the recorded angles are a constant pose between two moves that start quadratically
   in time, whatever way they take (straight, or round a finger in the way). Fitting
   that shape by least squares (:func:`fit_hold`) over the hold and the nearer part of
   both moves says when the hand arrived and left, to a fraction of a frame, and is far
   less sensitive to capture noise than a threshold on a differentiated signal.
5. Transitions are the times between consecutive holds.

Joint angles are the rotation vectors of every joint's rotation relative to its parent,
after retargeting the recording onto the hand model, so letter poses from the alphabet
and recorded frames are measured alike; the decomposition takes the forearm and wrist
together as the hand's turn (:func:`shape_angles`).
"""

import itertools
from dataclasses import dataclass

import numpy as np
from scipy.signal import savgol_filter

from synthesis.fingerspelling.alphabet import letter
from synthesis.fingerspelling.word_timing import TimingError, WordTiming
from synthesis.rigs.hand import HandModel
from synthesis.rigs.retarget import retarget
from synthesis.skeleton.kinematics import Pose
from synthesis.skeleton.motion import Motion

# Joint angles are smoothed over about this long before differentiating (5 frames at
# 60 fps): long enough to quiet sensor noise, short against a letter's hold.
SMOOTHING_S = 0.085
# An anchor matches its letter when the letter's decomposition weight there is at least
# this; most of a word's anchors must match, or the recording is of something else.
MATCH_WEIGHT = 0.5
MATCH_SHARE = 0.75
# A clip starts (ends) on a rest pose rather than on its first (last) letter when the
# hand is further from that letter than this share of the word's typical letter-to-
# letter distance.
LEAD_DISTANCE = 0.25
# A hold's fit spans the moves into and out of it up to this share of their way.
DEPARTURE_SHARE = 0.6
# Between two letters the hand speeds up by at least this share of its velocity range,
# and by this many times the velocity's spread while it is still (noise).
RISE = 0.01
NOISE_RISE = 3.0


class ExtractionError(TimingError):
    """The recording's letters could not be found."""


@dataclass(frozen=True)
class Extraction:
    """What was found: each letter's hold (start, end) in seconds and the timing.

    *velocity_rad_s* (n_frames,) is the mean joint angular speed and *weights*
    (n_frames, n_keys) the decomposition weights of the word's distinct key poses.
    """

    timing: WordTiming
    hold_bounds_s: np.ndarray
    velocity_rad_s: np.ndarray
    weights: np.ndarray

    @property
    def hold_frames(self) -> tuple[tuple[int, int], ...]:
        """Return each hold as whole frames ``[first, past_last)`` at the recording's rate."""
        rate = self.timing.metadata.get("rate_hz", 60.0)
        frames = []
        for start, end in self.hold_bounds_s * rate:
            first = int(np.ceil(start - 1e-9))
            frames.append((first, max(int(np.ceil(end - 1e-9)), first + 1)))
        return tuple(frames)


def joint_angles(pose: Pose, parents: np.ndarray) -> np.ndarray:
    """Return each frame's joint angles (n_frames, 3·n_joints) as rotation vectors.

    Each joint's rotation relative to its parent; a root's relative to the world, so that
    moving the whole forearm (the slide of a double letter) counts as motion too.
    """
    from scipy.spatial.transform import Rotation

    q = pose.quaternions
    columns = []
    for j in range(q.shape[1]):
        rotation = Rotation.from_quat(q[:, j])
        if parents[j] >= 0:
            rotation = Rotation.from_quat(q[:, parents[j]]).inv() * rotation
        columns.append(rotation.as_rotvec())
    return np.concatenate(columns, axis=1)


def hand_turn(pose: Pose, parents: np.ndarray) -> np.ndarray:
    """Return the hand's turn per frame (n_frames, 3): the wrist's rotation in the world."""
    from scipy.spatial.transform import Rotation

    wrist = int(np.flatnonzero(parents == 0)[0])
    return Rotation.from_quat(pose.quaternions[:, wrist]).as_rotvec()


def shape_angles(angles: np.ndarray, turn: np.ndarray, parents: np.ndarray) -> np.ndarray:
    """Return joint angles with the forearm's and wrist's replaced by the hand's *turn*.

    How a recording splits the hand's turn between forearm and wrist is the recording's
    own, not the alphabet's, so the two enter the match as one turn (issue 52: D, turned
    as human hands hold it, turns 76° by the forearm and 23° by the wrist).
    """
    wrist = int(np.flatnonzero(parents == 0)[0])
    return np.concatenate([turn, angles[:, 3 * (wrist + 1) :]], axis=1)


def _window(rate_hz: float) -> int:
    """Return the smoothing window in frames: odd, at least 5."""
    return max(round(SMOOTHING_S * rate_hz) | 1, 5)


def smooth_angles(angles: np.ndarray, rate_hz: float) -> np.ndarray:
    """Return joint angles (n_frames, m) smoothed by a quadratic Savitzky–Golay filter."""
    window = _window(rate_hz)
    if len(angles) <= window:
        return angles
    return savgol_filter(angles, window, 2, axis=0)


def angular_velocity(pose: Pose, rate_hz: float) -> np.ndarray:
    """Return the hand joints' mean angular speed per frame (rad/s), smoothed.

    Speeds are of the joints' world orientations, so a movement of the whole hand (the
    slide between double letters, the turn of J) counts for every joint, as it does for
    markers on a real hand.
    """
    q = pose.quaternions
    if len(q) < 2:
        return np.zeros(len(q))
    dots = np.abs(np.sum(q[1:] * q[:-1], axis=-1))
    speed = 2.0 * np.arccos(np.clip(dots, 0.0, 1.0)).mean(axis=1) * rate_hz
    speed = np.concatenate([speed[:1], speed])
    window = _window(rate_hz)
    if len(speed) > window:
        speed = np.maximum(savgol_filter(speed, window, 2), 0.0)
    return speed


def decompose(angles: np.ndarray, letter_angles: np.ndarray) -> np.ndarray:
    """Return per-frame weights (n_frames, n_letters) of ``J ≈ W · L`` (least squares)."""
    return angles @ np.linalg.pinv(letter_angles)


def fit_hold(angles: np.ndarray, arrives: bool, departs: bool) -> tuple[float, float]:
    """Return when (in samples, sub-sample) the hand arrives at a hold and leaves it.

    *angles* (n, m) span the hold and the nearer part of the moves into and out of it.
    The hand reaches and leaves a hold at rest with a continuous velocity, so whatever
    way it moves (straight, or round another finger) its angles are, by Taylor,
    ``p + a₂·τa² + a₃·τa³`` before the arrival ``ta`` (τa = ta − t), ``p`` during the
    hold and ``p + d₂·τd² + d₃·τd³`` after the departure ``td`` (τd = t − td). For each
    trial (ta, td) the pose and the vectors are a linear least-squares fit; the pair of
    the smallest residual wins, on a one-frame grid refined to a twentieth. Fitting both
    ends with one shared pose keeps a short hold from being swallowed by either move,
    and every sample of the window speaks, not only the few near the boundaries.
    *arrives*/*departs* False: the window starts/ends inside the hold.
    """
    n = len(angles)
    t = np.arange(n, dtype=float)

    def residual(ta: float, td: float) -> float:
        columns = [np.ones(n)]
        if arrives:
            tau = np.maximum(ta - t, 0.0)
            columns += [tau**2, tau**3]
        if departs:
            tau = np.maximum(t - td, 0.0)
            columns += [tau**2, tau**3]
        design = np.stack(columns, axis=1)
        coefficients = np.linalg.lstsq(design, angles, rcond=None)[0]
        return float(np.sum((design @ coefficients - angles) ** 2))

    def search(ta_values, td_values):
        best = (np.inf, 0.0, float(n - 1))
        for ta in ta_values if arrives else [0.0]:
            for td in td_values if departs else [float(n - 1)]:
                if td >= ta:
                    best = min(best, (residual(ta, td), ta, td))
        return best

    _, ta, td = search(np.arange(0.0, n - 1), np.arange(0.0, n - 1))
    for step in (0.25, 0.05):  # refine round the best
        near = np.arange(-4, 5) * step
        _, ta, td = search(np.clip(ta + near, 0, n - 1), np.clip(td + near, 0, n - 1))
    return ta, td


def _assign(scores: np.ndarray, velocity: np.ndarray, rise: float) -> list[int]:
    """Choose one frame per key, in increasing order, maximising the summed scores.

    *scores* is (n_keys, n_frames). Two consecutive keys' frames must have the hand
    speed up between them by at least *rise* (rad/s) over the faster of the two: each
    key is a separate slowing down, so a doubled letter cannot put both its anchors
    into one hold.
    """
    n_keys, n_frames = scores.shape
    # between[i, j]: the highest velocity strictly between frames i and j (i < j).
    between = np.full((n_frames, n_frames), -np.inf)
    for i in range(n_frames - 2):
        between[i, i + 2 :] = np.maximum.accumulate(velocity[i + 1 : -1])
    allowed = between >= np.maximum.outer(velocity, velocity) + rise
    best = scores[0].copy()
    back = np.zeros((n_keys, n_frames), dtype=int)
    for k in range(1, n_keys):
        options = np.where(allowed, best[:, None], -np.inf)  # (from i, to j)
        back[k] = np.argmax(options, axis=0)
        best = options[back[k], np.arange(n_frames)] + scores[k]
    if not np.isfinite(best).any():
        raise ExtractionError(
            f"The hand slows down fewer times than the word has letters ({n_keys}): "
            "is this a recording of that word?"
        )
    chosen = [int(np.argmax(best))]
    for k in range(n_keys - 1, 0, -1):
        chosen.append(int(back[k, chosen[-1]]))
    return chosen[::-1]


def _keys(letters: tuple[str, ...], side: str) -> tuple[list[tuple[int, int, str]], dict]:
    """Return the word's key poses in order as (letter index, 0 start | 1 end, name) and the
    distinct poses by name: one key for a still letter, two for J and Z's path ends."""
    keys, poses = [], {}
    for k, character in enumerate(letters):
        shape = letter(character, side)
        if shape.path_rad is None:
            keys.append((k, 0, character))
            poses[character] = shape.dofs_rad
        else:
            keys += [(k, 0, character + "0"), (k, 1, character + "1")]
            poses[character + "0"] = shape.path_rad[0]
            poses[character + "1"] = shape.path_rad[-1]
    return keys, poses


def extract(motion: Motion, word: str, side: str = "right") -> Extraction:
    """Return the holds and transitions of *word* in a recording of it being spelled."""
    letters = tuple(c.upper() for c in word if not c.isspace())
    if not letters:
        raise ExtractionError("Nothing to find: the word is empty.")
    model = HandModel(side)
    parents = model.skeleton.parents
    rate = motion.rate_hz
    keys, key_poses = _keys(letters, side)
    if motion.n_frames < 2 * len(keys):
        raise ExtractionError(
            f"The recording has {motion.n_frames} frames, too few to hold the "
            f"{len(letters)} letters of {''.join(letters)}: is this a recording of that word?"
        )
    pose = retarget(motion, model)
    raw = joint_angles(pose, parents)
    angles = smooth_angles(raw, rate)
    names = sorted(key_poses)
    letter_pose = model.pose(np.stack([key_poses[n] for n in names]))
    letter_angles = shape_angles(
        joint_angles(letter_pose, parents), hand_turn(letter_pose, parents), parents
    )
    # The smoothing is linear per column: the smoothed angles need only the turn's.
    recorded = shape_angles(angles, smooth_angles(hand_turn(pose, parents), rate), parents)
    if not recorded[:, :3].any():
        # Landmarks fitted in the palm's own frame (a .pose file) carry no turn of the
        # hand: the letters are matched on their handshapes alone.
        letter_angles[:, :3] = 0.0
    velocity = angular_velocity(pose, rate)
    weights = decompose(recorded, letter_angles)
    columns = [names.index(name) for _, _, name in keys]
    key_weights = weights[:, columns].T
    # Favour slow frames: of two frames where a letter is equally formed, the hold is
    # where the hand is stillest. Weights past 1 (a pose beyond the letter, on a detour
    # round a finger) count as 1.
    scores = np.clip(key_weights, 0.0, 1.0) - velocity / max(float(velocity.max()), 1e-9)
    quiet = velocity[velocity <= np.percentile(velocity, 25)]
    rise = max(RISE * float(np.ptp(velocity)), NOISE_RISE * float(quiet.std()))
    anchors = np.array(_assign(scores, velocity, rise))
    matched = np.mean(key_weights[np.arange(len(keys)), anchors] >= MATCH_WEIGHT)
    if matched < MATCH_SHARE:
        raise ExtractionError(
            f"The hand's poses where it slows down do not look like the letters of "
            f"{''.join(letters)} (only {100 * matched:.0f} % match): is this a recording of it?"
        )
    moves_in, moves_out = _moves_in_and_out(angles, velocity, anchors, rise)
    hold_bounds = _hold_bounds(keys, len(letters), _boundaries(raw, anchors, moves_in, moves_out))
    frame_ms = 1000.0 / rate
    hold_ms = tuple(max(end - start, 1.0) * frame_ms for start, end in hold_bounds)
    transition_ms = tuple(
        max(b[0] - a[1], 1.0) * frame_ms for a, b in itertools.pairwise(hold_bounds)
    )
    timing = WordTiming(letters, hold_ms, transition_ms, "mocap", {"rate_hz": rate})
    return Extraction(timing, hold_bounds / rate, velocity, weights)


def _moves_in_and_out(angles, velocity, anchors, rise: float) -> tuple[bool, bool]:
    """Return whether the hand moves in from a rest pose and out to one.

    It does if it speeds up before the first anchor (after the last) and ends up far
    from the letter; otherwise the clip starts (ends) on the letter.
    """
    steps = np.linalg.norm(np.diff(angles[anchors], axis=0), axis=1)
    far = LEAD_DISTANCE * (float(np.median(steps)) if len(steps) else 0.0)
    moves_in = (
        velocity[: anchors[0] + 1].max() >= velocity[anchors[0]] + rise
        and np.linalg.norm(angles[0] - angles[anchors[0]]) > far
    )
    moves_out = (
        velocity[anchors[-1] :].max() >= velocity[anchors[-1]] + rise
        and np.linalg.norm(angles[-1] - angles[anchors[-1]]) > far
    )
    return bool(moves_in), bool(moves_out)


def _hold_bounds(keys, n_letters: int, bounds) -> np.ndarray:
    """Return each letter's hold (n_letters, 2) in frames from its keys' arrive and leave."""
    hold_bounds = np.zeros((n_letters, 2))
    for (k, end, _), (arrive, leave) in zip(keys, bounds, strict=True):
        if end:
            hold_bounds[k, 1] = leave
        else:
            hold_bounds[k] = arrive, leave
    for k in range(n_letters - 1):  # fits that overlap meet halfway
        if hold_bounds[k, 1] > hold_bounds[k + 1, 0]:
            hold_bounds[k, 1] = hold_bounds[k + 1, 0] = hold_bounds[k, 1:].mean()
    return hold_bounds


def _boundaries(
    raw: np.ndarray, anchors: np.ndarray, moves_in: bool, moves_out: bool
) -> list[tuple[float, float]]:
    """Return, per anchor, when (in frames, sub-frame) the hand arrives at its pose and
    when it leaves it, from the recorded (unsmoothed) joint angles."""
    last = len(raw) - 1
    poses = raw[anchors]
    # The poses the hand comes from and goes to around each anchor: the neighbouring
    # anchors', the clip's ends for a move from or to rest.
    before = [raw[0] if moves_in else None, *poses[:-1]]
    after = [*poses[1:], raw[-1] if moves_out else None]
    bounds = []
    for k, at in enumerate(anchors):
        # The window runs from where the hand is 60 % of the way from the pose before to
        # where it is 60 % of the way to the pose after (or to the clip's ends).
        distance = np.linalg.norm(raw - poses[k], axis=1)
        lo, hi = 0, last
        if before[k] is not None:
            far = DEPARTURE_SHARE * np.linalg.norm(poses[k] - before[k])
            lo_at = np.flatnonzero(distance[: at + 1] > far)
            lo = int(lo_at[-1]) if lo_at.size else 0
        if after[k] is not None:
            far = DEPARTURE_SHARE * np.linalg.norm(after[k] - poses[k])
            hi_at = np.flatnonzero(distance[at:] > far)
            hi = at + int(hi_at[0]) if hi_at.size else last
        window = raw[lo : hi + 1]
        # Project onto the directions the hand comes from and goes to: two signals that
        # carry the moves, with the noise of two joint angles rather than of all of them.
        directions = [window[0] - poses[k], window[-1] - poses[k]]
        units = np.stack([d / max(np.linalg.norm(d), 1e-12) for d in directions], axis=1)
        ta, td = fit_hold((window - poses[k]) @ units, before[k] is not None, after[k] is not None)
        bounds.append((lo + ta, lo + td))
    return bounds
