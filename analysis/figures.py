"""Draw the report's figures with matplotlib (no display needed)."""

import textwrap
from pathlib import Path

import numpy as np

from analysis.plotting import pyplot
from analysis.report import Report


def _save(figure, out_dir: Path, name: str, formats: tuple[str, ...]) -> list[str]:
    written = []
    for extension in formats:
        path = out_dir / f"{name}.{extension}"
        # Fixed metadata keeps PDF output byte-stable between runs.
        metadata = {"CreationDate": None} if extension == "pdf" else {}
        figure.savefig(path, dpi=150, bbox_inches="tight", metadata=metadata)
        written.append(path.name)
    pyplot().close(figure)
    return written


def _wrapped(name: str, width: int = 14) -> str:
    """Break a long condition or item name onto lines, so tick labels keep apart."""
    return textwrap.fill(name, width, break_long_words=False) or name


def _tick_labels(axes, names: list[str], width_in: float) -> None:
    """Label the x ticks: wrapped side by side where they fit, else upright on one line."""
    wrapped = [_wrapped(name) for name in names]
    longest = max((max(len(line) for line in n.split("\n")) for n in wrapped), default=0)
    # About 0.09 in a character at 9 pt; a row of labels gets 80 % of the width.
    if longest * 0.09 * len(names) <= 0.8 * width_in:
        axes.set_xticks(range(len(names)), wrapped, fontsize=9)
    else:
        axes.set_xticks(range(len(names)), names, rotation=90, fontsize=9)


def participant_flow_plot(report: Report):
    """Draw the participant flow as bars: each stage's participants, each exclusion's."""
    flow = report.flow
    if flow is None:
        raise ValueError("The report has no participant flow to draw.")
    plt = pyplot()
    stages = [
        ("started", flow.started),
        ("consented", flow.consented),
        ("finished", flow.finished),
    ]
    excluded = [(f"excluded: {reason}", n) for reason, n in flow.excluded.items()]
    rows = [*stages, *excluded, ("analysed", flow.analysed)]
    figure, axes = plt.subplots(figsize=(6.0, 0.42 * len(rows) + 0.9))
    colours = ["#4a7ab5"] * len(stages) + ["#c0504d"] * len(excluded) + ["#2e7d32"]
    positions = np.arange(len(rows))[::-1]
    axes.barh(positions, [n for _, n in rows], color=colours)
    axes.set_yticks(positions, [name for name, _ in rows], fontsize=9)
    for position, (_, n) in zip(positions, rows, strict=True):
        axes.annotate(f" {n}", (n, position), va="center", fontsize=9)
    axes.set_xlabel("Participants")
    axes.set_xlim(0, max(1, flow.started) * 1.12)
    axes.set_title(f"Participant flow (from the {flow.source})", fontsize=10)
    figure.tight_layout()
    return figure


def participant_flow_figure(report: Report, out_dir: Path, formats=("png", "pdf")) -> list[str]:
    """Save :func:`participant_flow_plot` as participant_flow.<format>."""
    if report.flow is None:
        return []
    return _save(participant_flow_plot(report), out_dir, "participant_flow", formats)


def _pairwise(report: Report):
    if report.pairwise is None:
        raise ValueError("The report has no pairwise analysis to draw.")
    return report.pairwise


def condition_rates_plot(report: Report):
    """Draw the bar chart of per-participant win rates, mean ± SEM (seed 000 Fig. 5.4)."""
    plt = pyplot()
    conditions = _pairwise(report).conditions
    width = max(5.5, 1.3 * len(conditions) + 1.5)
    figure, axes = plt.subplots(figsize=(width, 3.8))
    means = [100 * c.mean_participant_rate for c in conditions]
    errors = [100 * c.sem if np.isfinite(c.sem) else 0 for c in conditions]
    axes.bar(range(len(conditions)), means, yerr=errors, capsize=4, color="#4a7ab5")
    _tick_labels(axes, [c.condition for c in conditions], width)
    axes.set_ylabel("Win rate: chosen / shown (%)")
    axes.set_title("Win rate per condition, mean ± SEM over participants", fontsize=10)
    axes.axhline(50, color="grey", linewidth=0.8, linestyle="--")
    axes.set_ylim(0, 100)
    figure.tight_layout()
    return figure


def condition_rates_figure(report: Report, out_dir: Path, formats=("png", "pdf")) -> list[str]:
    """Save :func:`condition_rates_plot` as condition_rates.<format>."""
    if report.pairwise is None:
        return []
    return _save(condition_rates_plot(report), out_dir, "condition_rates", formats)


def pairwise_matrix_plot(report: Report):
    """Draw the heat map: row condition's share of decisive judgements against column."""
    plt = pyplot()
    pairwise = _pairwise(report)
    names = [c.condition for c in pairwise.conditions]
    index = {name: i for i, name in enumerate(names)}
    matrix = np.full((len(names), len(names)), np.nan)
    for pair in pairwise.pairs:
        if pair.nobs:
            matrix[index[pair.a], index[pair.b]] = 100 * pair.a_wins / pair.nobs
            matrix[index[pair.b], index[pair.a]] = 100 * pair.b_wins / pair.nobs
    figure, axes = plt.subplots(figsize=(1.2 * len(names) + 3, 1.0 * len(names) + 2))
    image = axes.imshow(matrix, cmap="RdBu", vmin=0, vmax=100)
    # Labels stay on one line (wrapped, a row's would run into the next), columns' upright.
    axes.set_xticks(range(len(names)), names, rotation=90, fontsize=9)
    axes.set_yticks(range(len(names)), names, fontsize=9)
    for (row, column), value in np.ndenumerate(matrix):
        if np.isfinite(value):
            axes.text(column, row, f"{value:.0f} %", ha="center", va="center", fontsize=9)
    axes.set_xlabel("against")
    axes.set_ylabel("chosen")
    figure.colorbar(image, ax=axes, label="% of decisive judgements")
    return figure


def pairwise_matrix_figure(report: Report, out_dir: Path, formats=("png", "pdf")) -> list[str]:
    """Save :func:`pairwise_matrix_plot` as pairwise_matrix.<format>."""
    if report.pairwise is None:
        return []
    return _save(pairwise_matrix_plot(report), out_dir, "pairwise_matrix", formats)


def ratings_plot(frame):
    """Draw Tukey box plots of ratings per item, one panel per question (seed 003 Fig. 17);
    each item's conditions side by side in their own colour, named in the legend."""
    from analysis.ratings import rating_rows

    rows = rating_rows(frame)
    if rows.empty:
        return None
    plt = pyplot()
    questions = sorted(rows["question"].unique())
    conditions = sorted(rows["condition_a"].unique())
    items = sorted(rows["item"].unique())
    panel = max(3.2, 0.35 * len(items) * len(conditions) + 1)
    figure, axes = plt.subplots(
        1,
        len(questions),
        figsize=(panel * len(questions) + 1, 3.8),
        squeeze=False,
        layout="constrained",
    )
    colours = plt.get_cmap("tab10").colors
    step = 0.8 / len(conditions)
    # One legend entry per condition, whichever panel drew it first.
    handles: dict[str, object] = {}
    for axis, question in zip(axes[0], questions, strict=True):
        subset = rows[rows["question"] == question]
        for k, condition in enumerate(conditions):
            mine = subset[subset["condition_a"] == condition]
            present = [i for i, item in enumerate(items) if (mine["item"] == item).any()]
            if not present:
                continue
            data = [mine[mine["item"] == items[i]]["rating"].to_numpy() for i in present]
            offset = (k - (len(conditions) - 1) / 2) * step
            # Tukey box plots (whiskers at 1.5 IQR) with a black median, which the
            # default orange hid on orange boxes.
            parts = axis.boxplot(
                data,
                positions=[i + offset for i in present],
                widths=0.9 * step,
                whis=1.5,
                patch_artist=True,
                manage_ticks=False,
                medianprops={"color": "black", "linewidth": 1.5},
            )
            for box in parts["boxes"]:
                box.set(facecolor=colours[k % len(colours)], alpha=0.6)
            handles.setdefault(condition, parts["boxes"][0])
        _tick_labels(axis, list(items), panel)
        axis.set_title(question, fontsize=10)
    axes[0][0].set_ylabel("Rating")
    if len(conditions) > 1:
        figure.legend(
            list(handles.values()),
            list(handles),
            loc="outside lower center",
            ncols=min(len(conditions), 4),
            fontsize=9,
        )
    return figure


def all_figures(report: Report, frame, out_dir: Path, formats=("png", "pdf")) -> list[str]:
    """Save every figure the report has data for; return the file names written.

    *frame* is the table after exclusions, for the figures that show raw ratings.
    """
    return [
        *participant_flow_figure(report, out_dir, formats),
        *condition_rates_figure(report, out_dir, formats),
        *pairwise_matrix_figure(report, out_dir, formats),
        *ratings_figure(report, frame, out_dir, formats),
    ]


def ratings_figure(report: Report, frame, out_dir: Path, formats=("png", "pdf")) -> list[str]:
    """Save :func:`ratings_plot` as ratings_boxplots.<format>."""
    figure = ratings_plot(frame)
    if figure is None:
        return []
    return _save(figure, out_dir, "ratings_boxplots", formats)
