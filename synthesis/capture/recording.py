"""Turn captured landmarks into the engine's motions, and measure a capture's quality."""

from dataclasses import dataclass

import numpy as np

from synthesis.capture.handfit import HandFit, fit_hand
from synthesis.capture.posefile import PoseRecording
from synthesis.rigs.hand import HandModel
from synthesis.skeleton.motion import Motion


@dataclass(frozen=True)
class CapturedHand:
    """One hand of a recording fitted to the hand model: its motion and the fit."""

    motion: Motion
    fit: HandFit
    side: str

    def quality(self, recording: PoseRecording) -> dict:
        """Return the capture's quality figures (found share, confidence, residual, jitter)."""
        found = self.fit.found
        _, confidence = recording.hand(self.side)
        seen = self.fit.residual_mm[found]
        # Jitter: frame-to-frame change of the fitted finger DOFs' velocity (deg/frame²);
        # still holds give ~0, tracking noise raises it.
        dofs = np.degrees(self.fit.dofs_rad)
        jitter = float(np.abs(np.diff(dofs, n=2, axis=0)).mean()) if len(dofs) > 2 else 0.0
        return {
            "frames": recording.n_frames,
            "fps": recording.fps,
            "hands_found": recording.found_hands(),
            "side": self.side,
            "mean_confidence": float(confidence[found].mean()) if found.any() else 0.0,
            "residual_mm_median": float(np.median(seen)) if seen.size else None,
            "residual_mm_p95": float(np.percentile(seen, 95)) if seen.size else None,
            "jitter_deg_per_frame2": jitter,
            "depth": self.fit.depth,
            "metres_per_unit": self.fit.scale,
        }


def captured_hand(recording: PoseRecording, side: str = "right") -> CapturedHand:
    """Fit the hand model to one hand of *recording*; return its motion at the file's rate."""
    model = HandModel(side)
    points, confidence = recording.hand(side)
    fit = fit_hand(model, points, confidence, scale=None, rate_hz=recording.fps)
    motion = model.as_motion(fit.dofs_rad, recording.fps)
    return CapturedHand(motion, fit, side)
