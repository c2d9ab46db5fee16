"""Simulate a motion-capture performance of a fingerspelled word (a labelled stand-in).

No recordings ship with the project, yet the fingerspelling study has a Motion capture
condition and extraction needs recordings with known timing to be tested on. A simulated
performance is the nearest honest substitute, and says what it is in its timing's
metadata (``"simulated": True``):

- its timing is *sampled* from a Variable model rather than predicted: each hold drawn
  from the classifier's posterior over durations, each transition from the regression
  line plus its residual spread (seed 000 §4.2), so two performances of a word differ
  as two takes by a signer would;
- its motion is the spelled word plus what a capture adds: a slow wander of every joint
  (the hand never quite stops between letters, seed 000 §4.1) and sensor noise,
  each Gaussian noise low-passed with a Butterworth filter (:class:`CaptureNoise`).
"""

import itertools
from dataclasses import dataclass

import numpy as np

from synthesis.fingerspelling.word_timing import WordTiming
from synthesis.rigs.hand import HandModel
from synthesis.signing.noise import band_limited_noise
from synthesis.skeleton.motion import Motion
from synthesis.timing.bayes import CLASSES_MS
from synthesis.timing.features import word_features
from synthesis.timing.variable import VariableModel

# Residual spread of transitions around the regression line when the model does not
# record it: the published model's σ = 60 ms with r = 0.44 leaves 60·√(1 − r²) ≈ 54 ms.
DEFAULT_TRANSITION_SD_MS = 54.0


@dataclass(frozen=True)
class CaptureNoise:
    """How far a capture strays from the ideal motion, per DOF.

    *sensor_deg* is the RMS of measurement noise, band-limited to *sensor_hz* (a glove
    or marker solve at 60–120 fps); *wander_deg* the RMS of the slow drift of the whole
    hand, band-limited to *wander_hz*.
    """

    sensor_deg: float = 0.3
    sensor_hz: float = 10.0
    wander_deg: float = 1.0
    wander_hz: float = 1.5

    def sample(self, n_frames: int, n_dofs: int, rate_hz: float, rng: np.random.Generator):
        """Return noise (n_frames, n_dofs) in radians."""
        total = np.zeros((n_frames, n_dofs))
        for rms_deg, cutoff_hz in (
            (self.sensor_deg, self.sensor_hz),
            (self.wander_deg, self.wander_hz),
        ):
            if rms_deg > 0:
                total += np.radians(rms_deg) * band_limited_noise(
                    n_frames, n_dofs, cutoff_hz, rate_hz, rng
                )
        return total


def sample_timing(model: VariableModel, word: str, rng: np.random.Generator) -> WordTiming:
    """Return one performance's timing of *word*, drawn from *model*'s distributions."""
    letters = "".join(c for c in word.upper() if not c.isspace())
    holds = []
    for values in word_features(letters):
        log_p = model.holds.log_posterior(values)
        p = np.exp(log_p - log_p.max())
        holds.append(float(rng.choice(CLASSES_MS, p=p / p.sum())))
    spread = model.transitions.mean_abs_error_ms * np.sqrt(np.pi / 2)
    if not np.isfinite(spread) or spread <= 0:
        spread = DEFAULT_TRANSITION_SD_MS
    minimum = model.transitions.minimum_ms
    transitions = [
        max(model.transitions.predict_ms(a, b) + rng.normal(0.0, spread), minimum)
        for a, b in itertools.pairwise(letters)
    ]
    return WordTiming(
        tuple(letters),
        tuple(holds),
        tuple(transitions),
        "mocap",
        {"simulated": True, "model": model.metadata.get("name", "variable")},
    )


def simulate_recording(
    word: str,
    rng: np.random.Generator,
    model: VariableModel | None = None,
    side: str = "right",
    rate_hz: float = 60.0,
    noise: CaptureNoise | None = None,
    timing: WordTiming | None = None,
    lead_ms: float = 250.0,
) -> tuple[Motion, WordTiming]:
    """Return a simulated capture of *word* (a BVH-ready Motion) and its true timing.

    The timing is sampled from *model* (the published model when None) unless given;
    the word is spelled as :func:`synthesis.fingerspelling.spelling.spell` does, with *lead_ms*.
    """
    # Imported here: spelling uses this package's WordTiming, so a module-level import
    # would be circular.
    from synthesis.fingerspelling.spelling import spell, word_letters

    word_letters(word)  # AlphabetError names a character that is not a letter
    if timing is None:
        if model is None:
            from synthesis.timing.defaults import published_model

            model = published_model()
        timing = sample_timing(model, word, rng)
    noise = CaptureNoise() if noise is None else noise
    hand = HandModel(side)
    dofs = spell(word, side, rate_hz, timing, lead_ms)
    dofs = hand.clip(dofs + noise.sample(*dofs.shape, rate_hz, rng))
    return hand.as_motion(dofs, rate_hz), timing
