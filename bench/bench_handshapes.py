"""Classify real signers' letters, fitted onto our hand, by orientation-free handshape
features: does the fitted hand still show the letter the signer made?

    .venv/bin/python bench/bench_handshapes.py

The human letters are the spoken-to-signed package's ASL lexicon (a test dependency).
Each recording's middle frame is fitted (synthesis.capture.fidelity.view_of); the fitted
hand's landmarks, turned as the fit turned them and seen in the image plane like the
recording (its files have no depth), are classified by nearest features
(synthesis.capture.features) among the 26 human letters. Prints each letter's
residual and the letter it is taken for, then the count right. Then each whole
recording is fitted as the platform fits a recording (tracked frame to frame) and its
middle frame classified the same way.
"""

import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from synthesis.capture import fit_hand, read_pose
from synthesis.capture.features import handshape_features, nearest_handshape
from synthesis.capture.fidelity import seen_as, view_of
from synthesis.capture.lexicon import human_letter_files
from synthesis.rigs.hand import HandModel
from synthesis.rigs.landmarks import landmarks


def main() -> int:
    model = HandModel()
    started = time.perf_counter()
    views = {
        k: view_of(model, *read_pose(p).hand("right")) for k, p in human_letter_files().items()
    }
    human = {letter: view.features for letter, view in views.items()}
    fitted = {letter: seen_as(model, view.dofs_rad, view) for letter, view in views.items()}
    residuals = {letter: view.residual_mm for letter, view in views.items()}
    elapsed = time.perf_counter() - started
    right = 0
    for letter in human:
        taken = nearest_handshape(fitted[letter], human)
        right += taken == letter
        print(f"{letter}: residual {residuals[letter]:5.1f} mm, classified as {taken}")
    print(f"fitted letters classified right: {right} of {len(human)}")
    print(
        f"median residual {np.median(list(residuals.values())):.1f} mm; "
        f"fit and features {1000 * elapsed / len(human):.0f} ms per letter"
    )
    tracked, frames, started = 0, 0, time.perf_counter()
    for letter, path in human_letter_files().items():
        points, confidence = read_pose(path).hand("right")
        flat = points * [1, 1, 0]
        fit = fit_hand(model, flat, confidence)
        middle = len(points) // 2
        marks = np.einsum(
            "ij,kj->ki", fit.rotations[middle], landmarks(model, fit.dofs_rad[middle])
        )
        marks[:, 2] = 0.0
        tracked += nearest_handshape(handshape_features(marks), human) == letter
        frames += len(points)
    elapsed = time.perf_counter() - started
    print(
        f"whole recordings, tracked: {tracked} of {len(human)} middle frames classified right "
        f"({frames / elapsed:.1f} frames/s)"
    )
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
