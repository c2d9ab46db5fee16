"""Figures of the spine condition: torso angles over time, spine on against off.

:func:`torso_angles_figure` plots the whole spine's forward bend, side bend and twist
(the three spine joints summed, degrees) over a sentence for both versions, with the
keys marked, so a researcher sees what the automated motion adds and when.
"""

import numpy as np

from synthesis.signing.sentence import SPINE_JOINTS, Sentence

ANGLES = (
    ("flexion", "forward bend"),
    ("side_bend", "side bend (to the left +)"),
    ("rotation", "twist (right shoulder forward +)"),
)


def torso_angles(sentence: Sentence) -> dict[str, np.ndarray]:
    """Return the whole spine's flexion, side bend and rotation (degrees) per frame."""
    names = sentence.body.dof_names
    out = {}
    for angle, _ in ANGLES:
        columns = [names.index(f"{joint}_{angle}") for joint in SPINE_JOINTS]
        out[angle] = np.degrees(sentence.dofs_rad[:, columns].sum(axis=1))
    return out


def torso_angles_figure(on: Sentence, off: Sentence, title: str = ""):
    """Return a matplotlib figure: torso bend and twist over time, spine on vs off."""
    from synthesis.plotting import pyplot

    plt = pyplot()

    figure, axes = plt.subplots(len(ANGLES), 1, figsize=(8, 6), sharex=True)
    for sentence, label, colour in ((on, "spine on", "#1f77b4"), (off, "spine off", "#d62728")):
        times = np.arange(len(sentence.dofs_rad)) / sentence.rate_hz
        for axis, values in zip(axes, torso_angles(sentence).values(), strict=True):
            axis.plot(times, values, label=label, color=colour, linewidth=1.4)
    for axis, (_, caption) in zip(axes, ANGLES, strict=True):
        axis.set_ylabel(f"{caption}\n(°)", fontsize=8)
        for key in on.key_times_s:
            axis.axvline(key, color="#cccccc", linewidth=0.5, zorder=0)
    axes[-1].set_xlabel("time (s)")
    axes[0].legend(loc="upper right", fontsize=8)
    if title:
        axes[0].set_title(title, fontsize=9)
    figure.tight_layout()
    return figure
