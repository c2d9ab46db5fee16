"""Write a capture's quality report: figures, a plot, and with the video a contact sheet.

Kept apart from :mod:`synthesis.capture.recording` (which turns landmarks into motion)
so that the data module writes no files and the contact sheet, which draws fitted
hands, can import the recording without a circle.
"""

import json
from pathlib import Path

import numpy as np

from synthesis.capture.posefile import PoseRecording
from synthesis.capture.recording import CapturedHand


def write_report(
    hand: CapturedHand,
    recording: PoseRecording,
    directory: str | Path,
    video: str | Path | None = None,
) -> Path:
    """Write quality.json and quality.png (residual and hand found, per frame) into
    *directory*, and with the *video* captured, contact.png (synthesis.capture.contact)."""
    from synthesis.plotting import pyplot

    plt = pyplot()

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
