"""Spell a word with a simple default timing: equal holds, smooth transitions.

This is the placeholder every clip can use before a study picks a timing model (motion
capture, variable, constant, normalised constant: the timing issue builds those).
Letters are held for ``hold_ms`` and joined by ``transition_ms`` of eased interpolation
of the hand's DOFs; J and Z play their motion paths over ``path_ms``; a doubled letter
(the LL of HELLO) slides outward and back while held twice (seed 000 §5.2 "the bounce
between double letters").
"""

from dataclasses import dataclass

import numpy as np
from scipy.interpolate import PchipInterpolator

from synthesis.alphabet import AlphabetError, letter
from synthesis.hand import HandModel

# A relaxed, slightly open hand between words.
REST_DEGREES = {
    **{f"{f}_mcp_flexion": 20.0 for f in ("index", "middle", "ring", "pinky")},
    **{f"{f}_pip_flexion": 25.0 for f in ("index", "middle", "ring", "pinky")},
    "thumb_cmc_flexion": 10.0,
    "thumb_mcp_flexion": 10.0,
}
DOUBLE_SLIDE_DEG = 7.0


@dataclass(frozen=True)
class SpellingTiming:
    """Durations of the simple timing, milliseconds."""

    hold_ms: float = 200.0
    transition_ms: float = 180.0
    path_ms: float = 450.0
    rest_ms: float = 250.0


def word_letters(word: str) -> list[str]:
    """Return the letters of *word* in upper case; AlphabetError names anything else."""
    letters = [c.upper() for c in word if not c.isspace()]
    if not letters:
        raise AlphabetError("Nothing to spell: the word is empty.")
    for c in letters:
        letter(c)  # raises AlphabetError with the offending character
    return letters


def spelling_keys(
    word: str, side: str = "right", timing: SpellingTiming = SpellingTiming()
) -> tuple[np.ndarray, np.ndarray]:
    """Return key times (k,) in seconds and key poses (k, n_dofs) for spelling *word*."""
    model = HandModel(side)
    rest = model.from_degrees(REST_DEGREES)
    slide = model.dof_names.index("forearm_tilt_side")
    times, poses = [0.0], [rest]
    t = timing.rest_ms / 1000
    previous = None
    for character in word_letters(word):
        shape = letter(character, side)
        t += timing.transition_ms / 1000
        if shape.path_rad is not None:
            for fraction, pose in zip(shape.path_times, shape.path_rad, strict=True):
                times.append(t + fraction * timing.path_ms / 1000)
                poses.append(np.array(pose))
            t += timing.path_ms / 1000
        else:
            pose = np.array(shape.dofs_rad)
            if character == previous:
                # Slide away from the midline for the repeat: −x for a right hand.
                pose[slide] += np.radians(DOUBLE_SLIDE_DEG) * (1 if side == "right" else -1)
            times += [t, t + timing.hold_ms / 1000]
            poses += [pose, pose]
            t += timing.hold_ms / 1000
        previous = character
    t += timing.transition_ms / 1000 + timing.rest_ms / 1000
    times.append(t)
    poses.append(rest)
    return np.array(times), np.stack(poses)


def spell(
    word: str,
    side: str = "right",
    rate_hz: float = 60.0,
    timing: SpellingTiming = SpellingTiming(),
) -> np.ndarray:
    """Return the hand's DOF vectors (n_frames, n_dofs) spelling *word* at *rate_hz*.

    Keys are joined by a monotone cubic (PCHIP), which eases in and out of holds without
    overshooting a pose (no finger flexes past where either letter puts it).
    """
    times, poses = spelling_keys(word, side, timing)
    count = int(np.floor(times[-1] * rate_hz + 1e-9)) + 1
    frames = PchipInterpolator(times, poses, axis=0)(np.arange(count) / rate_hz)
    return HandModel(side).clip(frames)
