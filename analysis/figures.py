"""Draw the report's figures with matplotlib (no display needed)."""

from pathlib import Path

import numpy as np

from analysis.report import Report


def _pyplot():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def _save(figure, out_dir: Path, name: str, formats: tuple[str, ...]) -> list[str]:
    written = []
    for extension in formats:
        path = out_dir / f"{name}.{extension}"
        # Fixed metadata keeps PDF output byte-stable between runs.
        metadata = {"CreationDate": None} if extension == "pdf" else {}
        figure.savefig(path, dpi=150, bbox_inches="tight", metadata=metadata)
        written.append(path.name)
    _pyplot().close(figure)
    return written


def condition_rates_figure(report: Report, out_dir: Path, formats=("png", "pdf")) -> list[str]:
    """Bar chart of per-participant win rates, mean ± SEM (seed 000 Fig. 5.4)."""
    if report.pairwise is None:
        return []
    plt = _pyplot()
    conditions = report.pairwise.conditions
    figure, axes = plt.subplots(figsize=(5.5, 3.6))
    means = [100 * c.mean_participant_rate for c in conditions]
    errors = [100 * c.sem if np.isfinite(c.sem) else 0 for c in conditions]
    axes.bar([c.condition for c in conditions], means, yerr=errors, capsize=4, color="#4a7ab5")
    axes.set_ylabel("Win rate: chosen / shown (%)")
    axes.set_title("Win rate per condition, mean ± SEM over participants", fontsize=10)
    axes.axhline(50, color="grey", linewidth=0.8, linestyle="--")
    axes.set_ylim(0, 100)
    return _save(figure, out_dir, "condition_rates", formats)


def pairwise_matrix_figure(report: Report, out_dir: Path, formats=("png", "pdf")) -> list[str]:
    """Heat map: row condition's share of decisive judgements against column condition."""
    if report.pairwise is None:
        return []
    plt = _pyplot()
    names = [c.condition for c in report.pairwise.conditions]
    index = {name: i for i, name in enumerate(names)}
    matrix = np.full((len(names), len(names)), np.nan)
    for pair in report.pairwise.pairs:
        if pair.nobs:
            matrix[index[pair.a], index[pair.b]] = 100 * pair.a_wins / pair.nobs
            matrix[index[pair.b], index[pair.a]] = 100 * pair.b_wins / pair.nobs
    figure, axes = plt.subplots(figsize=(1.2 * len(names) + 2, 1.0 * len(names) + 1.5))
    image = axes.imshow(matrix, cmap="RdBu", vmin=0, vmax=100)
    axes.set_xticks(range(len(names)), names, rotation=30, ha="right")
    axes.set_yticks(range(len(names)), names)
    for (row, column), value in np.ndenumerate(matrix):
        if np.isfinite(value):
            axes.text(column, row, f"{value:.0f} %", ha="center", va="center", fontsize=9)
    axes.set_xlabel("against")
    axes.set_ylabel("chosen")
    figure.colorbar(image, ax=axes, label="% of decisive judgements")
    return _save(figure, out_dir, "pairwise_matrix", formats)


def ratings_figure(report: Report, frame, out_dir: Path, formats=("png", "pdf")) -> list[str]:
    """Tukey box plots of ratings per item, one panel per question (seed 003 Fig. 17)."""
    from analysis.ratings import rating_rows

    rows = rating_rows(frame)
    if rows.empty:
        return []
    plt = _pyplot()
    questions = sorted(rows["question"].unique())
    figure, axes = plt.subplots(
        1, len(questions), figsize=(3.2 * len(questions) + 1, 3.4), squeeze=False
    )
    for axis, question in zip(axes[0], questions, strict=True):
        subset = rows[rows["question"] == question]
        groups = sorted(subset.groupby(["item", "condition_a"]).groups)
        data = [
            subset[(subset["item"] == i) & (subset["condition_a"] == c)]["rating"].to_numpy()
            for i, c in groups
        ]
        labels = [i if subset["condition_a"].nunique() == 1 else f"{i}\n{c}" for i, c in groups]
        axis.boxplot(data, whis=1.5, tick_labels=labels)  # Tukey: whiskers at 1.5 IQR
        axis.set_title(question, fontsize=10)
        axis.tick_params(axis="x", labelsize=8)
    axes[0][0].set_ylabel("Rating")
    return _save(figure, out_dir, "ratings_boxplots", formats)
