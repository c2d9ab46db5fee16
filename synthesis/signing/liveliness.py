"""Liveliness: small coherent noise on every major joint, so held postures still live.

Seed 003 §3.6: an avatar perfectly at rest reads as a still image, yet noise that is too
large or too fast makes it tremble. Tuned just above visibility, following anatomy:
amplitude falls and frequency rises toward distal joints, and joints not under
purposeful control (the weak hand of a one-handed sign) move more. The noise is the
same in both conditions of the spine study (spec 03): it is not what is tested.
"""

from dataclasses import dataclass, field

import numpy as np

from synthesis.rigs.body import BodyModel
from synthesis.rigs.face import EYE_DOF_NAMES, is_face_dof
from synthesis.signing.noise import band_limited_noise

# Per joint group: (peak amplitude in degrees, cutoff frequency in Hz), proximal to
# distal. The project's tuning (the seed gives guidelines, not numbers).
DEFAULT_GROUPS = {
    "spine": (0.6, 0.4),
    "neck": (0.8, 0.5),
    "head": (0.8, 0.6),
    "clavicle": (0.4, 0.6),
    "shoulder": (0.8, 0.7),
    "elbow": (0.7, 0.9),
    "forearm": (0.6, 1.2),
    "wrist": (0.6, 1.4),
    "fingers": (0.3, 1.8),
}


def joint_group(dof_name: str) -> str:
    """Return the liveliness group of a body DOF ("spine", "shoulder", "fingers", …);
    the face's are "eyes" and "face" (synthesis.rigs.face)."""
    if dof_name in EYE_DOF_NAMES:
        return "eyes"
    if is_face_dof(dof_name):
        return "face"
    name = dof_name.removeprefix("right_").removeprefix("left_")
    head = name.split("_")[0]
    if head in ("spine", "neck", "head", "clavicle", "shoulder", "elbow", "forearm", "wrist"):
        return head
    return "fingers"


@dataclass(frozen=True)
class Liveliness:
    """Noise settings: per group (peak degrees, cutoff Hz); the weak side's factor."""

    groups: dict = field(default_factory=lambda: dict(DEFAULT_GROUPS))
    weak_factor: float = 1.8

    def sample(
        self, body: BodyModel, n_frames: int, rate_hz: float, rng: np.random.Generator
    ) -> np.ndarray:
        """Return noise (n_frames, n_dofs) in radians, each DOF peaking at its amplitude.

        The face channels get none: the face moves as the face technique says (its
        blinks, its non-manual signals), and the body's noise is drawn as before.
        """
        body_dofs = np.array([not is_face_dof(name) for name in body.dof_names])
        names = [name for name, kept in zip(body.dof_names, body_dofs, strict=True) if kept]
        weak = "left_" if body.dominant == "right" else "right_"
        amplitude = np.empty(len(names))
        cutoff = np.empty(len(names))
        for i, name in enumerate(names):
            amplitude[i], cutoff[i] = self.groups[joint_group(name)]
            if name.startswith(weak):
                amplitude[i] *= self.weak_factor
        noise = band_limited_noise(n_frames, len(names), cutoff, rate_hz, rng)
        # Scaled to the peak, like Perlin noise's bounded range, so no frame overshoots.
        noise /= np.abs(noise).max(axis=0, keepdims=True).clip(1e-12)
        out = np.zeros((n_frames, len(body.dof_names)))
        out[:, body_dofs] = noise * np.radians(amplitude)
        return out
