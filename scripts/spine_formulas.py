"""Plot the torso's bend and twist on the story sentences: seed 003's formula and the variant.

    .venv/bin/python scripts/spine_formulas.py docs/img/spine-formulas.png

One row per story sentence (spec 03): the bend's size and the twist over time, spine on,
with ``spine_formula`` ``seed`` (§3.1 as printed, the default) and ``comfort`` (the
comfort-radius variant), the same c0–c3. Prints each sentence's mean and largest bend.
"""

import argparse
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from synthesis.plotting import pyplot
from synthesis.signing.sentence import SentenceOptions, synthesize
from synthesis.signing.sentence_plots import torso_angles
from synthesis.signing.spine import FORMULAS, SpineParams
from synthesis.signing.stories import SPINE_STORY

COLOURS = {"seed": "#1f77b4", "comfort": "#d62728"}


def bend_and_twist(text: str, formula: str) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Return times (s), the torso's bend size and its twist (degrees) per frame."""
    sentence = synthesize(text, SentenceOptions(params=SpineParams(formula=formula)))
    angles = torso_angles(sentence)
    times = np.arange(len(sentence.dofs_rad)) / sentence.rate_hz
    return times, np.hypot(angles["flexion"], angles["side_bend"]), angles["rotation"]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out", type=Path)
    args = parser.parse_args()
    plt = pyplot()
    figure, axes = plt.subplots(len(SPINE_STORY), 2, figsize=(11, 2.1 * len(SPINE_STORY)))
    print("sentence | formula | mean bend (°) | largest bend (°) | twist range (°)")
    for row, text in enumerate(SPINE_STORY):
        for formula in FORMULAS:
            times, bend, twist = bend_and_twist(text, formula)
            label = "seed 003 as printed" if formula == "seed" else "comfort-radius variant"
            axes[row, 0].plot(times, bend, color=COLOURS[formula], label=label, linewidth=1.3)
            axes[row, 1].plot(times, twist, color=COLOURS[formula], linewidth=1.3)
            twist_range = f"{twist.min():.1f} to {twist.max():.1f}"
            print(f"S{row + 1} | {formula} | {bend.mean():.1f} | {bend.max():.1f} | {twist_range}")
        axes[row, 0].set_ylabel(f"S{row + 1}\nbend (°)", fontsize=8)
        axes[row, 1].set_ylabel("twist (°)", fontsize=8)
    axes[0, 0].set_title("torso bend (flexion and side bend together)", fontsize=9)
    axes[0, 1].set_title("torso twist (positive: right shoulder forward)", fontsize=9)
    axes[0, 0].legend(fontsize=8, loc="upper right")
    for axis in axes[-1]:
        axis.set_xlabel("time (s)")
    figure.suptitle("Spine on, c0–c3 at their defaults (16°, 20°, 12°, 12°)", fontsize=10)
    figure.tight_layout()
    figure.savefig(args.out, dpi=110)


if __name__ == "__main__":
    main()
