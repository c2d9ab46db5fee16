"""Figures researchers expect of the timing conditions (matplotlib, PNG or PDF).

- :func:`timeline_figure`: one word's holds and transitions under each condition, side
  by side on one time axis.
- :func:`trajectory_figure`: the average finger joint angle over time under each
  condition (after seed 000 Fig. 4.10), from the synthesized (or retimed) motions.
"""

from pathlib import Path

import numpy as np

from synthesis.fingerspelling.word_timing import WordTiming
from synthesis.plotting import pyplot

COLOURS = {
    "mocap": "#4d4d4d",
    "variable": "#1f77b4",
    "constant": "#d62728",
    "normalized": "#ff7f0e",
    "simple": "#2ca02c",
}


def timeline_figure(timings: dict[str, WordTiming]):
    """Return a figure of each condition's holds (dark, lettered) and transitions (light)."""
    plt = pyplot()
    figure, axes = plt.subplots(figsize=(8, 0.7 + 0.55 * len(timings)))
    for row, (condition, timing) in enumerate(timings.items()):
        colour = COLOURS.get(condition, "#555555")
        starts = timing.hold_starts_ms()
        axes.broken_barh(
            list(zip(starts, timing.hold_ms, strict=True)), (row - 0.3, 0.6), facecolors=colour
        )
        moves = [
            (s + h, t)
            for s, h, t in zip(starts, timing.hold_ms, timing.transition_ms, strict=False)
        ]
        axes.broken_barh(moves, (row - 0.15, 0.3), facecolors=colour, alpha=0.3)
        for start, hold, name in zip(starts, timing.hold_ms, timing.letters, strict=True):
            axes.text(
                start + hold / 2,
                row,
                name,
                ha="center",
                va="center",
                color="white",
                fontsize=8,
                fontweight="bold",
            )
        axes.text(timing.total_ms + 20, row, f"{timing.total_ms:.0f} ms", va="center", fontsize=8)
    axes.set_yticks(range(len(timings)), list(timings))
    axes.invert_yaxis()
    axes.set_xlabel("time from the first hold (ms)")
    word = next(iter(timings.values())).word
    axes.set_title(f"{word}: holds (letters) and transitions by condition", fontsize=10)
    longest = max(t.total_ms for t in timings.values())
    axes.set_xlim(0, longest * 1.15)
    figure.tight_layout()
    return figure


def trajectory_figure(motions: dict[str, np.ndarray], rate_hz: float, word: str):
    """Return a figure of the mean finger flexion over time per condition.

    *motions* maps a condition to hand-model DOF vectors (n_frames, n_dofs).
    """
    from synthesis.rigs.hand import HandModel

    plt = pyplot()
    names = HandModel().dof_names
    flexion = [
        i
        for i, name in enumerate(names)
        if name.endswith("_flexion") and not name.startswith("wrist")
    ]
    figure, axes = plt.subplots(figsize=(8, 3.2))
    for condition, dofs in motions.items():
        times = np.arange(len(dofs)) / rate_hz
        mean = np.degrees(np.asarray(dofs)[:, flexion].mean(axis=1))
        axes.plot(times, mean, label=condition, color=COLOURS.get(condition), linewidth=1.5)
    axes.set_xlabel("time (s)")
    axes.set_ylabel("mean finger flexion (°)")
    axes.set_title(f"{word}: average joint angle over time by condition", fontsize=10)
    axes.legend(fontsize=8, frameon=False)
    figure.tight_layout()
    return figure


def write_figure(figure, path: str | Path) -> Path:
    """Write a figure as PNG or PDF (by the extension), byte-stable for PDFs, and close it."""
    path = Path(path)
    metadata = {"CreationDate": None} if path.suffix.lower() == ".pdf" else {}
    figure.savefig(path, dpi=150, bbox_inches="tight", metadata=metadata)
    pyplot().close(figure)
    return path
