"""Turn captured landmarks into the engine's motions, and report a capture's quality."""

import json
from dataclasses import dataclass
from pathlib import Path

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


def write_report(hand: CapturedHand, recording: PoseRecording, directory: str | Path,
                 video: str | Path | None = None) -> Path:  # fmt: skip
    """Write quality.json and quality.png (residual and hand found, per frame) into
    *directory*, and with the *video* captured, contact.png (synthesis.capture.contact)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    directory = Path(directory)
    directory.mkdir(parents=True, exist_ok=True)
    report = hand.quality(recording)
    (directory / "quality.json").write_text(json.dumps(report, indent=2) + "\n", "utf-8")
    seconds = np.arange(recording.n_frames) / recording.fps
    figure, (top, bottom) = plt.subplots(2, 1, figsize=(8, 4.5), sharex=True)
    top.plot(seconds, np.median(hand.fit.residual_mm, axis=1), color="#345")
    top.set_ylabel("fit residual (mm)\nmedian of 21 points")
    bottom.step(seconds, hand.fit.found.astype(int), where="mid", color="#a33")
    bottom.set_ylabel(f"{hand.side} hand\nfound")
    bottom.set_yticks([0, 1], ["no", "yes"])
    bottom.set_xlabel("time (s)")
    figure.tight_layout()
    figure.savefig(directory / "quality.png", dpi=110)
    plt.close(figure)
    if video is not None:
        from synthesis.capture.contact import write_contact_sheet

        write_contact_sheet(hand, video, directory / "contact.png")
    return directory
