"""Spell a word: letter poses from the alphabet, placed in time by a :class:`WordTiming`.

Letters are held for their hold time and joined by eased interpolation over their
transition time, through intermediate poses where the fingers would otherwise pass
through each other (synthesis.fingerspelling.routes); J and Z play their motion paths during their
hold; a doubled letter (the LL of HELLO) slides outward for the repeat (seed 000 §5.2
"the bounce between double letters"). The clip starts and ends on a relaxed hand held still for
``REST_HOLD_MS``, ``lead_ms`` of eased movement away from the word, so neither the
first frame nor the last gives away how the word is timed.

Without a timing, :func:`simple_timing` is used: equal holds and transitions, the
placeholder every clip can use before a study picks a timing model.
"""

import itertools

import numpy as np
from scipy.interpolate import CubicSpline, PchipInterpolator

from synthesis.fingerspelling.alphabet import AlphabetError, letter, rest_pose
from synthesis.fingerspelling.alphabets import DEFAULT_ALPHABET, as_letter, manual_alphabet
from synthesis.fingerspelling.routes import REST, letter_route, route_poses
from synthesis.fingerspelling.word_timing import WordTiming
from synthesis.rigs.hand import HandModel

DOUBLE_SLIDE_DEG = 7.0
SIMPLE_HOLD_MS = 200.0
SIMPLE_PATH_MS = 450.0
SIMPLE_TRANSITION_MS = 180.0
LEAD_MS = 250.0
REST_HOLD_MS = 100.0


def word_letters(word: str, alphabet: str = DEFAULT_ALPHABET) -> list[str]:
    """Return the letters of *word* in upper case, composed (NFC: "c" and a combining
    cedilla are one "Ç"); AlphabetError names a character the alphabet lacks, or a
    two-handed alphabet (spelling moves one hand so far)."""
    manual = manual_alphabet(alphabet)
    letters = [c for c in as_letter(word) if not c.isspace()]
    if not letters:
        raise AlphabetError("Nothing to spell: the word is empty.")
    for c in letters:
        manual.check(c)
    if manual.two_handed:
        raise AlphabetError(
            f"The {manual.name} manual alphabet is two-handed: the engine reads its "
            "letters but spells words with one hand only so far."
        )
    return letters


def simple_timing(word: str, alphabet: str = DEFAULT_ALPHABET) -> WordTiming:
    """Return the simple default timing: 200 ms holds (450 ms for a letter that moves,
    as J and Z do), 180 ms moves."""
    letters = word_letters(word, alphabet)
    moving = {c for c in letters if letter(c, alphabet=alphabet).path_rad is not None}
    holds = [SIMPLE_PATH_MS if c in moving else SIMPLE_HOLD_MS for c in letters]
    return WordTiming(
        tuple(letters), tuple(holds), (SIMPLE_TRANSITION_MS,) * (len(letters) - 1), "simple"
    )


def hold_times_s(timing: WordTiming, lead_ms: float = LEAD_MS) -> np.ndarray:
    """Return each letter's hold (start, end) in seconds, (n_letters, 2), in the clip
    :func:`spell` makes with *lead_ms*."""
    if lead_ms < 0:
        raise ValueError(f"lead_ms must not be negative, not {lead_ms!r}.")
    still = REST_HOLD_MS if lead_ms else 0.0
    starts = (still + lead_ms + timing.hold_starts_ms()) / 1000
    return np.stack([starts, starts + np.asarray(timing.hold_ms) / 1000], axis=1)


def spelling_keys(
    timing: WordTiming,
    side: str = "right",
    lead_ms: float = LEAD_MS,
    alphabet: str = DEFAULT_ALPHABET,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Return key times (k,) in seconds, key poses (k, n_dofs) and which keys are the
    intermediate poses of a routed transition (k,) for a timed word."""
    word_letters(timing.word, alphabet)
    model = HandModel(side)
    rest = rest_pose(side)
    slide = model.dof_names.index("forearm_tilt_side")
    outward = np.radians(DOUBLE_SLIDE_DEG) * (1 if side == "right" else -1)
    holds = hold_times_s(timing, lead_ms)
    lead = lead_ms / 1000
    still = REST_HOLD_MS / 1000 if lead else 0.0
    # Without a lead the clip starts and ends on the letters themselves.
    times, poses = ([0.0, still], [rest, rest]) if lead else ([], [])
    via_at: list[int] = []
    for k, character in enumerate(timing.letters):
        shape = letter(character, side, alphabet)
        start, hold = holds[k, 0], timing.hold_ms[k] / 1000
        if k or lead:
            previous = timing.letters[k - 1] if k else REST
            route = letter_route(previous, character, alphabet)
            _add_route(times, poses, via_at, route, start, side, shape)
        if shape.path_rad is not None:
            times += list(start + shape.path_times * hold)
            poses += [np.array(pose) for pose in shape.path_rad]
            continue
        pose = np.array(shape.dofs_rad)
        if k and character == timing.letters[k - 1]:
            pose[slide] += outward
        times += [start, start + hold]
        poses += [pose, pose]
    if lead:
        end_s = times[-1] + lead
        route = letter_route(timing.letters[-1], REST, alphabet)
        _add_route(times, poses, via_at, route, end_s, side, None, rest)
        times += [end_s, end_s + still]
        poses += [rest, rest]
    vias = np.zeros(len(times), dtype=bool)
    vias[via_at] = True
    return np.array(times), np.stack(poses), vias


def _add_route(times, poses, via_at, route, arrive_s, side, shape, target=None):
    """Append the intermediate keys of *route* that keep the fingers clear of each other
    between the previous letter's last key and this letter's first
    (fingerspelling.routes)."""
    if route == "direct":
        return
    if target is None:
        target = shape.dofs_rad if shape.path_rad is None else shape.path_rad[0]
    vias = route_poses(route, poses[-1], target, side)
    leave_s = times[-1]
    for i, via in enumerate(vias, start=1):
        times.append(leave_s + (arrive_s - leave_s) * i / (len(vias) + 1))
        via_at.append(len(poses))
        poses.append(via)


def spell(
    word: str,
    side: str = "right",
    rate_hz: float = 60.0,
    timing: WordTiming | None = None,
    lead_ms: float = LEAD_MS,
    alphabet: str = DEFAULT_ALPHABET,
) -> np.ndarray:
    """Return the hand's DOF vectors (n_frames, n_dofs) spelling *word* at *rate_hz* in
    the manual *alphabet*.

    Keys are joined by a monotone cubic (PCHIP), which eases in and out of holds without
    overshooting a pose (no finger flexes past where either letter puts it); a routed
    transition by a clamped cubic spline through its intermediate poses.
    """
    timing = timing or simple_timing(word, alphabet)
    if timing.word != "".join(word_letters(word, alphabet)):
        raise ValueError(f"The timing is for {timing.word}, not {word.upper()}.")
    times, poses, vias = spelling_keys(timing, side, lead_ms, alphabet)
    count = int(np.floor(times[-1] * rate_hz + 1e-9)) + 1
    if len(times) == 1:  # one letter, no lead: a still
        return HandModel(side).clip(np.repeat(poses, count, axis=0))
    at = np.arange(count) / rate_hz
    frames = PchipInterpolator(times[~vias], poses[~vias], axis=0)(at)
    # A routed transition sweeps through its intermediate poses on a spline at rest at
    # both ends (synthesis.fingerspelling.routes.route_path), not stopping at each.
    keys = np.flatnonzero(~vias)
    for first, last in itertools.pairwise(keys):
        if last - first > 1:
            span = slice(first, last + 1)
            spline = CubicSpline(times[span], poses[span], axis=0, bc_type="clamped")
            inside = (at > times[first]) & (at < times[last])
            frames[inside] = spline(at[inside])
    return HandModel(side).clip(frames)
