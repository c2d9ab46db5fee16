"""Spell a word: letter poses from the alphabet, placed in time by a :class:`WordTiming`.

Letters are held for their hold time and joined by eased interpolation over their
transition time; J and Z play their motion paths during their hold; a doubled letter
(the LL of HELLO) slides outward for the repeat (seed 000 §5.2 "the bounce between
double letters"). The clip starts and ends on a relaxed hand held still for
``REST_HOLD_MS``, ``lead_ms`` of eased movement away from the word, so neither the
first frame nor the last gives away how the word is timed.

Without a timing, :func:`simple_timing` is used: equal holds and transitions, the
placeholder every clip can use before a study picks a timing model.
"""

import numpy as np
from scipy.interpolate import PchipInterpolator

from synthesis.alphabet import AlphabetError, letter
from synthesis.hand import HandModel
from synthesis.timing.word import WordTiming

# A relaxed, slightly open hand between words.
REST_DEGREES = {
    **{f"{f}_mcp_flexion": 20.0 for f in ("index", "middle", "ring", "pinky")},
    **{f"{f}_pip_flexion": 25.0 for f in ("index", "middle", "ring", "pinky")},
    "thumb_cmc_flexion": 10.0,
    "thumb_mcp_flexion": 10.0,
}
DOUBLE_SLIDE_DEG = 7.0
SIMPLE_HOLD_MS = 200.0
SIMPLE_PATH_MS = 450.0
SIMPLE_TRANSITION_MS = 180.0
LEAD_MS = 250.0
REST_HOLD_MS = 100.0


def word_letters(word: str) -> list[str]:
    """Return the letters of *word* in upper case; AlphabetError names anything else."""
    letters = [c.upper() for c in word if not c.isspace()]
    if not letters:
        raise AlphabetError("Nothing to spell: the word is empty.")
    for c in letters:
        letter(c)  # raises AlphabetError with the offending character
    return letters


def simple_timing(word: str) -> WordTiming:
    """Return the simple default timing: 200 ms holds (450 ms for J and Z), 180 ms moves."""
    letters = word_letters(word)
    holds = [SIMPLE_PATH_MS if c in "JZ" else SIMPLE_HOLD_MS for c in letters]
    return WordTiming(
        tuple(letters), tuple(holds), (SIMPLE_TRANSITION_MS,) * (len(letters) - 1), "simple"
    )


def spelling_keys(
    timing: WordTiming, side: str = "right", lead_ms: float = LEAD_MS
) -> tuple[np.ndarray, np.ndarray]:
    """Return key times (k,) in seconds and key poses (k, n_dofs) for a timed word."""
    word_letters(timing.word)
    model = HandModel(side)
    rest = model.from_degrees(REST_DEGREES)
    slide = model.dof_names.index("forearm_tilt_side")
    outward = np.radians(DOUBLE_SLIDE_DEG) * (1 if side == "right" else -1)
    if lead_ms < 0:
        raise ValueError(f"lead_ms must not be negative, not {lead_ms!r}.")
    lead = lead_ms / 1000
    still = REST_HOLD_MS / 1000 if lead else 0.0
    # Without a lead the clip starts and ends on the letters themselves.
    times, poses = ([0.0, still], [rest, rest]) if lead else ([], [])
    starts = still + lead + timing.hold_starts_ms() / 1000
    for k, character in enumerate(timing.letters):
        shape = letter(character, side)
        start, hold = starts[k], timing.hold_ms[k] / 1000
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
        times += [times[-1] + lead, times[-1] + lead + still]
        poses += [rest, rest]
    return np.array(times), np.stack(poses)


def spell(
    word: str,
    side: str = "right",
    rate_hz: float = 60.0,
    timing: WordTiming | None = None,
    lead_ms: float = LEAD_MS,
) -> np.ndarray:
    """Return the hand's DOF vectors (n_frames, n_dofs) spelling *word* at *rate_hz*.

    Keys are joined by a monotone cubic (PCHIP), which eases in and out of holds without
    overshooting a pose (no finger flexes past where either letter puts it).
    """
    timing = timing or simple_timing(word)
    if timing.word != "".join(word_letters(word)):
        raise ValueError(f"The timing is for {timing.word}, not {word.upper()}.")
    times, poses = spelling_keys(timing, side, lead_ms)
    count = int(np.floor(times[-1] * rate_hz + 1e-9)) + 1
    if len(times) == 1:  # one letter, no lead: a still
        return HandModel(side).clip(np.repeat(poses, count, axis=0))
    frames = PchipInterpolator(times, poses, axis=0)(np.arange(count) / rate_hz)
    return HandModel(side).clip(frames)
