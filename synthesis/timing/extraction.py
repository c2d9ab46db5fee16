"""Find the letter holds and transitions in a recording of a fingerspelled word (seed 000 §4.1).

1. The hand's average angular velocity per frame: holds sit at its local minima (the
   hand slows almost to a stop, except after the last letter, where it does stop).
2. Word decomposition: every frame's joint angles as a least-squares mix of the word's
   letter poses, ``J_i ≈ Σ_k w_ik L_k`` via the pseudo-inverse (seed 000 eqs. 4.1–4.2);
   a letter's weight peaks where it is formed.
3. The minima are matched to the letters in order, choosing for each letter the minimum
   where its weight is highest (dynamic programming keeps the order), and a hold spans
   the frames around its minimum where the velocity stays near that minimum.
4. Transitions are the times between consecutive holds.

Joint angles are the rotation vectors of every joint's rotation relative to its parent,
after retargeting the recording onto the hand model, so letter poses from the alphabet
and recorded frames are measured alike.
"""

import itertools
from dataclasses import dataclass

import numpy as np
from scipy.signal import find_peaks, savgol_filter

from synthesis.alphabet import letter
from synthesis.hand import HandModel
from synthesis.kinematics import Pose
from synthesis.motion import Motion
from synthesis.retarget import retarget
from synthesis.timing.word import TimingError, WordTiming

# A hold ends where the velocity has risen this far from its minimum toward the
# neighbouring peak (low enough to stop at the first frames of motion), or three
# times the capture's noise above it, whichever is higher.
HOLD_LEVEL = 0.08
NOISE_MARGIN = 3.0
# A hold matches its letter when the letter's decomposition weight there is at least
# this; most of a word's holds must match, or the recording is of something else.
MATCH_WEIGHT = 0.5
MATCH_SHARE = 0.75


class ExtractionError(TimingError):
    """The recording's letters could not be found."""


@dataclass(frozen=True)
class Extraction:
    """What was found: per-letter hold frames and the resulting timing."""

    timing: WordTiming
    hold_frames: tuple[tuple[int, int], ...]
    velocity_rad_s: np.ndarray
    weights: np.ndarray


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


def angular_velocity(pose: Pose, rate_hz: float, window: int = 5) -> np.ndarray:
    """Return the hand joints' mean angular speed per frame (rad/s), lightly smoothed.

    Speeds are of the joints' world orientations, so a movement of the whole hand (the
    slide between double letters, the turn of J) counts for every joint, as it does for
    markers on a real hand.
    """
    q = pose.quaternions
    dots = np.abs(np.sum(q[1:] * q[:-1], axis=-1))
    speed = 2.0 * np.arccos(np.clip(dots, 0.0, 1.0)).mean(axis=1) * rate_hz
    speed = np.concatenate([speed[:1], speed])
    if len(speed) > window:
        speed = np.maximum(savgol_filter(speed, window, 2), 0.0)
    return speed


def decompose(angles: np.ndarray, letter_angles: np.ndarray) -> np.ndarray:
    """Return per-frame weights (n_frames, n_letters) of ``J ≈ W · L`` (least squares)."""
    return angles @ np.linalg.pinv(letter_angles)


def _assign(minima: np.ndarray, scores: np.ndarray) -> list[int]:
    """Choose one minimum per letter, in order, maximising the summed letter weights.

    *scores* is (n_letters, n_minima); returns the chosen minima's positions in *minima*.
    """
    n_letters, n_minima = scores.shape
    best = np.full((n_letters, n_minima), -np.inf)
    back = np.zeros((n_letters, n_minima), dtype=int)
    best[0] = scores[0]
    for k in range(1, n_letters):
        running, where = -np.inf, -1
        for m in range(n_minima):
            if m >= 1 and best[k - 1, m - 1] > running:
                running, where = best[k - 1, m - 1], m - 1
            if where >= 0:
                best[k, m] = running + scores[k, m]
                back[k, m] = where
    chosen = [int(np.argmax(best[-1]))]
    for k in range(n_letters - 1, 0, -1):
        chosen.append(int(back[k, chosen[-1]]))
    return chosen[::-1]


def extract(motion: Motion, word: str, side: str = "right") -> Extraction:
    """Return the holds and transitions of *word* in a recording of it being spelled."""
    letters = tuple(c.upper() for c in word if not c.isspace())
    if not letters:
        raise ExtractionError("Nothing to find: the word is empty.")
    model = HandModel(side)
    parents = model.skeleton.parents
    rate = motion.rate_hz
    pose = retarget(motion, model)
    angles = joint_angles(pose, parents)
    unique = sorted(set(letters))
    letter_angles = joint_angles(
        model.pose(np.stack([letter(c, side).dofs_rad for c in unique])), parents
    )
    velocity = angular_velocity(pose, rate)
    weights = decompose(angles, letter_angles)
    # Minima of the velocity: peaks of its negative, at least a frame apart.
    minima, _ = find_peaks(-velocity, prominence=0.05 * float(np.ptp(velocity) or 1.0))
    # A recording that stops on its last letter has no minimum after it: the clip's
    # end then stands in for one.
    candidates = minima
    if len(candidates) < len(letters):
        candidates = np.unique(np.concatenate([minima, [len(velocity) - 1]]))
    if len(candidates) < len(letters):
        raise ExtractionError(
            f"Found {len(candidates)} places where the hand slows down, but {word.upper()} "
            f"has {len(letters)} letters: is this a recording of that word?"
        )
    columns = [unique.index(c) for c in letters]
    scores = np.stack([weights[candidates, col] for col in columns])
    picks = _assign(candidates, scores)
    matched = np.mean([scores[k, m] >= MATCH_WEIGHT for k, m in enumerate(picks)])
    if matched < MATCH_SHARE:
        raise ExtractionError(
            f"The hand's poses where it slows down do not look like the letters of "
            f"{word.upper()} (only {100 * matched:.0f} % match): is this a recording of it?"
        )
    chosen = candidates[picks]
    bounds = np.concatenate([[0], chosen, [len(velocity) - 1]])
    quiet = velocity[velocity <= np.percentile(velocity, 25)]
    noise = NOISE_MARGIN * float(quiet.std()) if quiet.size > 1 else 0.0
    spans = [
        _hold_span(velocity, int(bounds[k + 1]), int(bounds[k]), int(bounds[k + 2]), noise)
        for k in range(len(chosen))
    ]
    frame_ms = 1000.0 / rate
    # Durations from the sub-frame boundaries; at least a frame each.
    hold_ms = tuple(max(end - start, 1.0) * frame_ms for start, end in spans)
    transition_ms = tuple(max(b[0] - a[1], 1.0) * frame_ms for a, b in itertools.pairwise(spans))
    timing = WordTiming(letters, hold_ms, transition_ms, "mocap", {"rate_hz": rate})
    frames = tuple((int(np.ceil(start)), max(int(np.ceil(end)), int(np.ceil(start)) + 1))
                   for start, end in spans)  # fmt: skip
    return Extraction(timing, frames, velocity, weights)


def _hold_span(
    velocity: np.ndarray, at: int, before: int, after: int, noise: float
) -> tuple[float, float]:
    """Return the start and end (in frames, sub-frame) of the hold around frame *at*.

    *before* and *after* are the neighbouring holds' minima (or the clip's ends): the
    transition peaks in between set how far the velocity may rise within this hold, and
    a hold never reaches past them, so neighbouring holds cannot overlap. ``velocity[t]``
    is the motion from frame t − 1 to t, so it belongs to time t − ½; the boundaries are
    where it crosses the limit, interpolated linearly between those half frames.
    """
    floor = velocity[at]
    left_peak_at = before + int(np.argmax(velocity[before : at + 1]))
    right_peak_at = at + int(np.argmax(velocity[at : after + 1]))
    limit_left = floor + max(HOLD_LEVEL * (velocity[left_peak_at] - floor), noise)
    limit_right = floor + max(HOLD_LEVEL * (velocity[right_peak_at] - floor), noise)
    start = at
    while start > left_peak_at + 1 and velocity[start - 1] <= limit_left:
        start -= 1
    end = at + 1
    while end < right_peak_at and velocity[end] <= limit_right:
        end += 1
    start_s = start - 0.5 - _crossing(velocity[start - 1], velocity[start], limit_left)
    end_s = end - 1.5 + _crossing(velocity[end - 1], velocity[min(end, len(velocity) - 1)],
                                  limit_right)  # fmt: skip
    return start_s, max(end_s, start_s)


def _crossing(inside: float, outside: float, limit: float) -> float:
    """Return how far (0–1) from the *inside* sample toward *outside* the limit is crossed."""
    if outside <= inside:
        return 0.0
    return float(np.clip((limit - inside) / (outside - inside), 0.0, 1.0))
