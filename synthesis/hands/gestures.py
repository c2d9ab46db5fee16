"""Simulate free-hand conversational gestures: the stand-in for seed 000 §3.1's gesture capture.

Seed 000 §3.1.4 built its database from an actor "performing common conversational
gestures" and then gesticulating in conversation, over 10,000 frames at 120 Hz, and
tested on a sequence withheld from it. No such capture ships here, so this module
simulates one (and every output that uses it says *simulated*): a stream of key
handshapes drawn from gesture archetypes (relaxed, open palm, point, fist, counting two
to five, pinch, cup, beckon), each perturbed per finger and per joint, with the wrist
flexed and deviated, joined by minimum-jerk strokes of 0.2–0.7 s and short holds that
drift. Fingers curl together through one curl value per finger (MCP, PIP and DIP in the
proportions of a natural flexion), so the digits are correlated the way a hand's are
but no two keys are the same. Different generators give held-out sequences.
"""

import numpy as np

from synthesis.rigs.hand import FINGERS, HandModel
from synthesis.skeleton.retime import minimum_jerk

# Joint angles at full curl (deg) of a finger: MCP, PIP, DIP flexion.
FULL_CURL_DEG = (85.0, 100.0, 70.0)
# Thumb postures: CMC abduction, rotation, flexion; MCP, IP flexion (deg).
THUMB_DEG = {
    "relaxed": (20.0, 10.0, 10.0, 15.0, 15.0),
    "out": (55.0, 0.0, -10.0, 0.0, 0.0),
    "across": (10.0, 40.0, 40.0, 50.0, 45.0),
    "opposed": (45.0, 50.0, 25.0, 25.0, 30.0),
}
# Archetypes: curl of index, middle, ring, pinky (0 straight, 1 full), spread
# (deg between neighbours), thumb posture.
ARCHETYPES = {
    "relaxed": ((0.25, 0.3, 0.35, 0.4), 4.0, "relaxed"),
    "open palm": ((0.0, 0.0, 0.0, 0.0), 6.0, "out"),
    "point": ((0.0, 0.9, 0.95, 0.95), 0.0, "across"),
    "fist": ((0.95, 0.95, 0.95, 0.95), 0.0, "across"),
    "two": ((0.0, 0.0, 0.95, 0.95), 10.0, "across"),
    "three": ((0.0, 0.0, 0.0, 0.95), 8.0, "across"),
    "four": ((0.0, 0.0, 0.0, 0.0), 8.0, "across"),
    "five": ((0.0, 0.0, 0.0, 0.0), 15.0, "out"),
    "pinch": ((0.55, 0.15, 0.2, 0.25), 2.0, "opposed"),
    "cup": ((0.45, 0.45, 0.45, 0.45), 2.0, "opposed"),
    "beckon": ((0.6, 0.85, 0.9, 0.9), 0.0, "relaxed"),
}
# Each finger's share of the archetype's spread, from the thumb side (index) outwards.
SPREAD_SHARE = {"index": 1.5, "middle": 0.5, "ring": -0.5, "pinky": -1.5}
STROKE_S = (0.2, 0.7)
HOLD_S = (0.05, 0.45)


def key_pose(hand: HandModel, archetype: str, rng: np.random.Generator) -> np.ndarray:
    """Return one key handshape (hand DOFs, rad): *archetype* perturbed, the wrist placed."""
    curls, spread_deg, thumb = ARCHETYPES[archetype]
    dofs = np.degrees(hand.neutral())
    names = hand.dof_names
    shift = rng.normal(0.0, 0.08)
    for finger, curl in zip(FINGERS, curls, strict=True):
        amount = np.clip(curl + shift + rng.normal(0.0, 0.07), -0.05, 1.0)
        ratios = np.clip(1.0 + rng.normal(0.0, 0.12, 3), 0.6, 1.4)
        for joint, full, ratio in zip(("mcp", "pip", "dip"), FULL_CURL_DEG, ratios, strict=True):
            dofs[names.index(f"{finger}_{joint}_flexion")] = amount * full * ratio
        spread = SPREAD_SHARE[finger] * spread_deg
        dofs[names.index(f"{finger}_mcp_abduction")] = spread + rng.normal(0.0, 2.0)
    thumb_names = ("cmc_abduction", "cmc_rotation", "cmc_flexion", "mcp_flexion", "ip_flexion")
    for name, angle in zip(thumb_names, THUMB_DEG[thumb], strict=True):
        dofs[names.index(f"thumb_{name}")] = angle + rng.normal(0.0, 6.0)
    dofs[names.index("wrist_flexion")] = rng.normal(0.0, 18.0)
    dofs[names.index("wrist_deviation")] = rng.normal(-3.0, 7.0)
    return hand.clip(np.radians(dofs))


def simulate_gestures(
    hand: HandModel, seconds: float, rate_hz: float, rng: np.random.Generator
) -> np.ndarray:
    """Return *seconds* of simulated free-hand gesturing (n_frames, hand DOFs) at *rate_hz*.

    Archetypes are drawn uniformly; a hold drifts by a small random offset so that no
    frame repeats exactly.
    """
    archetypes = tuple(ARCHETYPES)
    total = max(2, round(seconds * rate_hz))
    frames = [key_pose(hand, archetypes[rng.integers(len(archetypes))], rng)[None, :]]
    count = 1
    while count < total:
        start = frames[-1][-1]
        target = key_pose(hand, archetypes[rng.integers(len(archetypes))], rng)
        stroke = max(2, round(rng.uniform(*STROKE_S) * rate_hz))
        profile = minimum_jerk(np.arange(1, stroke + 1) / stroke)[:, None]
        frames.append(start + profile * (target - start))
        hold = max(1, round(rng.uniform(*HOLD_S) * rate_hz))
        drift = np.radians(rng.normal(0.0, 1.5, target.shape))
        frames.append(target + minimum_jerk(np.arange(1, hold + 1) / hold)[:, None] * drift)
        count += stroke + hold
    return hand.clip(np.vstack(frames)[:total])
