"""Write a DOF reduction's report: seed 002 Tables 1–5, errors per DOF, a figure."""

import textwrap
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from synthesis.hands.reconstruct import LWR_VARIANCE
from synthesis.hands.reduction import (
    SEED_STEPS,
    Reduction,
    apply_reduction,
    find_reduction,
    reconstruction_error_deg,
)
from synthesis.tables import write_csv, write_latex

# Seed 002 Table 5: free DOFs of two hands (50 curves) after each step.
PUBLISHED_STEPS = (39, 27, 31, 15)
PUBLISHED_REDUCTION_INPUT = "seed 002: one 27 s motion capture of two hands (50 curves)"
RECONSTRUCTION_COLUMNS = {
    "markers": "m",
    "error_cm": "error (cm)",
    "sd_cm": "s.d.",
    "published_cm": "published (cm)",
    "published_sd_cm": "pub. s.d.",
}
STEP_COLUMNS = {
    "step": "step",
    "input": "input",
    "dofs": "DOFs",
    "of": "of",
    "mean_error_deg": "mean error (deg)",
    "published_dofs_of_50": "published DOFs of 50",
}


def step_rows(curves_deg: np.ndarray, names, source: str = "") -> list[dict]:
    """Return Table 5's rows for these curves: DOFs and mean error after each seed step,
    beside the published counts; *source* says what the curves are."""
    rows = []
    for (range_deg, rmsd), published in zip(SEED_STEPS, PUBLISHED_STEPS, strict=True):
        reduction = find_reduction(curves_deg, names, range_deg, rmsd)
        errors = reconstruction_error_deg(curves_deg, apply_reduction(curves_deg, reduction))
        step = f"range < {range_deg:g}" + (f" + rmsd < {rmsd:g}" if rmsd is not None else "")
        rows.append(
            {
                "step": step,
                "input": source,
                "dofs": reduction.dof_count,
                "of": len(names),
                "mean_error_deg": round(float(errors.mean()), 3),
                "max_error_deg": round(float(errors.max()), 3),
                "published_dofs_of_50": published,
                "published_input": PUBLISHED_REDUCTION_INPUT,
            }
        )
    return rows


def write_reduction_report(
    curves_deg: np.ndarray,
    reduction: Reduction,
    directory: str | Path,
    source: str,
    steps: list[dict] | None = None,
) -> list[Path]:
    """Write the reduction of *curves_deg* (the analysis curves) to *directory*.

    *source* says what the motion was (a recording, the engine's spelling, simulated):
    every table's caption repeats it, as the published figures came from captures.
    *steps*: Table 5's rows (:func:`step_rows`) when already computed.
    """
    directory = Path(directory)
    directory.mkdir(parents=True, exist_ok=True)
    errors = reconstruction_error_deg(curves_deg, apply_reduction(curves_deg, reduction))
    written = _reduction_tables(curves_deg, reduction, errors, directory)
    steps = steps or step_rows(curves_deg, reduction.names, source)
    written.append(write_csv(directory / "steps.csv", steps, list(steps[0])))
    caption = f"Free DOFs after seed 002's steps: {source}; published: {PUBLISHED_REDUCTION_INPUT}"
    written.append(write_latex(directory / "steps.tex", steps, STEP_COLUMNS, caption))
    summary = directory / "report.md"
    summary.write_text(_reduction_summary(curves_deg, reduction, errors, steps, source), "utf-8")
    written += [summary, _plot_steps(steps, directory / "dofs-vs-error.png", source)]
    return written


def _reduction_tables(curves_deg, reduction: Reduction, errors, directory: Path) -> list[Path]:
    """Write the constant curves, the relations and each curve's error as CSV."""
    means = curves_deg.mean(axis=0)
    irrelevant = [
        {
            "curve": n,
            "range_deg": round(reduction.ranges_deg[n], 3),
            "mean_deg": round(reduction.constant[n], 3),
        }
        for n in reduction.constant
    ]
    relations = [
        {
            "dependent": r.dependent,
            "controlling": r.controller,
            "metric": r.metric,
            "rmsd": round(r.rmsd, 3),
            "pair_rmsd": round(r.pair_rmsd, 3),
        }
        for r in reduction.relations
    ]
    curves = [
        {
            "curve": n,
            "role": _role(reduction, n),
            "mean_deg": round(float(m), 3),
            "range_deg": round(reduction.ranges_deg[n], 3),
            "rms_error_deg": round(float(e), 4),
        }
        for n, m, e in zip(reduction.names, means, errors, strict=True)
    ]
    return [
        write_csv(directory / "irrelevant.csv", irrelevant, ["curve", "range_deg", "mean_deg"]),
        write_csv(
            directory / "relations.csv",
            relations,
            ["dependent", "controlling", "metric", "rmsd", "pair_rmsd"],
        ),
        write_csv(
            directory / "errors.csv",
            curves,
            ["curve", "role", "mean_deg", "range_deg", "rms_error_deg"],
        ),
    ]


def _reduction_summary(curves_deg, reduction: Reduction, errors, steps, source: str) -> str:
    """Return report.md: the thresholds, the motion, the free DOFs and Table 5's steps."""
    names = reduction.names
    lines = [
        f"# DOF reduction (seed 002): range < {reduction.range_deg:g}°"
        + (f", rmsd < {reduction.rmsd:g}" if reduction.rmsd == reduction.rmsd else ""),
        "",
        f"Motion: {source}. {len(curves_deg)} frames at 30 fps, {len(names)} curves. The "
        "published figures (seed 002) come from one 27 s motion-capture performance of "
        "two hands; figures from other motions are not comparable one to one.",
        "",
        f"Free DOFs: {reduction.dof_count} of {len(names)} "
        f"({len(reduction.constant)} constant, {len(reduction.relations)} rebuilt). "
        f"Reconstruction error: mean {errors.mean():.3f}°, largest {errors.max():.3f}° "
        f"({names[int(np.argmax(errors))]}).",
        "",
        "| step | DOFs | mean error (°) | published DOFs (of 50) |",
        "|---|---|---|---|",
        *(
            f"| {r['step']} | {r['dofs']} of {r['of']} | {r['mean_error_deg']} | "
            f"{r['published_dofs_of_50']} |"
            for r in steps
        ),
        "",
    ]
    return "\n".join(lines)


def _role(reduction: Reduction, name: str) -> str:
    if name in reduction.constant:
        return "constant"
    for relation in reduction.relations:
        if relation.dependent == name:
            return f"from {relation.controller}"
    return "free"


def _plot_steps(steps: list[dict], path: Path, source: str) -> Path:
    from synthesis.plotting import pyplot

    plt = pyplot()

    figure, axes = plt.subplots(figsize=(5.6, 3.6))
    # Steps that land on the same point share one label: overprinted text is unreadable.
    points: dict[tuple, list[str]] = {}
    for row in steps:
        points.setdefault((row["dofs"], row["mean_error_deg"]), []).append(row["step"])
    ordered = sorted(points)
    axes.plot([p[0] for p in ordered], [p[1] for p in ordered], "o-")
    # Neighbouring points' labels alternate above and below so that they do not meet.
    for k, point in enumerate(ordered):
        below = k % 2 == 1
        axes.annotate(
            "\n".join(points[point]),
            point,
            fontsize=7,
            textcoords="offset points",
            xytext=(4, -4 if below else 4),
            va="top" if below else "bottom",
        )
    axes.margins(x=0.3, y=0.2)
    axes.set_xlabel("free DOFs")
    axes.set_ylabel("mean reconstruction error (°)")
    axes.set_title(f"DOF count vs reconstruction error\n{textwrap.fill(source, 60)}", fontsize=9)
    figure.tight_layout()
    figure.savefig(path, dpi=120)
    plt.close(figure)
    return path


@dataclass(frozen=True, eq=False)
class ReconstructionErrors:
    """The error by marker count (1–13) of rebuilding a hand motion, and what it was on."""

    method: str
    source: str
    database: str
    ranking: list[dict]
    rows: list[dict]


def reconstruction_errors(
    motion, method: str, source: str, database_path: str = "", variance: float = LWR_VARIANCE
) -> ReconstructionErrors:
    """Return the marker ranking and the error by marker count of reconstructing *motion*
    (a hand), each row beside seed 000 Table 3.1's p = 1000 figure where there is one."""
    from synthesis.hands.evaluation import PUBLISHED_INPUT, PUBLISHED_TABLE_3_1
    from synthesis.hands.handover import pose_database, reconstruct_hand
    from synthesis.hands.markers import MARKERS, rank_markers, virtual_markers
    from synthesis.hands.reconstruct import marker_error_cm
    from synthesis.rigs.hand import HandModel

    if not isinstance(motion.rig, HandModel):
        raise ValueError("The reconstruction report takes a hand motion (not the body).")
    side = motion.rig.side
    database = pose_database(side, database_path)
    order, influence = rank_markers(database.markers)
    ranking = [
        {"rank": k + 1, "marker": MARKERS[i], "influence": round(float(influence[i]), 6)}
        for k, i in enumerate(order)
    ]
    hand = HandModel(side)
    truth = virtual_markers(hand, motion.dofs_rad, database.root)
    # Table 3.1's p = 1000 row is the nearest-pose method's; LWR's errors were only plotted.
    published = PUBLISHED_TABLE_3_1[1000] if method == "nearest" else {}
    rows = []
    for count in range(1, len(MARKERS) + 1):
        rebuilt = reconstruct_hand(
            motion.dofs_rad, side, motion.rate_hz, count, method, database_path, variance
        )
        error, spread = marker_error_cm(truth, virtual_markers(hand, rebuilt, database.root))
        paper = published.get(count, (None, None))
        rows.append(
            {
                "markers": count,
                "method": method,
                "input": source,
                "database": database.source,
                "error_cm": round(error, 3),
                "sd_cm": round(spread, 3),
                "published_cm": paper[0],
                "published_sd_cm": paper[1],
                "published_input": PUBLISHED_INPUT if paper[0] is not None else "",
            }
        )
    return ReconstructionErrors(method, source, database.source, ranking, rows)


def write_reconstruction_report(errors: ReconstructionErrors, directory: str | Path) -> list[Path]:
    """Write the marker ranking, the errors by marker count (CSV, LaTeX) and a figure of
    marker count against error to *directory*."""
    directory = Path(directory)
    directory.mkdir(parents=True, exist_ok=True)
    caption = (
        f"Mean marker error (cm) by markers kept ({errors.method}): {errors.source}; "
        f"database: {errors.database}; published: seed 000 Table 3.1, p = 1000 (nearest "
        "pose only)"
    )
    title = (
        f"Marker count vs reconstruction error ({errors.method})\n{errors.source}; "
        f"database: {errors.database}"
    )
    rows = errors.rows
    return [
        write_csv(
            directory / "marker-ranking.csv", errors.ranking, ["rank", "marker", "influence"]
        ),
        write_csv(directory / "errors-by-markers.csv", rows, list(rows[0])),
        write_latex(directory / "errors-by-markers.tex", rows, RECONSTRUCTION_COLUMNS, caption),
        _plot_markers(rows, directory / "markers-vs-error.png", title),
    ]


def _plot_markers(rows: list[dict], path: Path, title: str) -> Path:
    from synthesis.plotting import pyplot

    plt = pyplot()
    figure, axes = plt.subplots(figsize=(5.6, 3.8))
    axes.plot([r["markers"] for r in rows], [r["error_cm"] for r in rows], "o-", label="ours")
    published = [r for r in rows if r["published_cm"] is not None]
    if published:
        axes.plot(
            [r["markers"] for r in published],
            [r["published_cm"] for r in published],
            "s",
            fillstyle="none",
            label="seed 000 Table 3.1, p = 1000",
        )
        axes.legend(fontsize=8)
    axes.set_xlabel("markers kept (PCA rank order)")
    axes.set_ylabel("mean marker error (cm)")
    # Sources and databases are long: wrap them rather than let the title run off the page.
    lines = [textwrap.fill(line, 80) for line in title.splitlines()]
    axes.set_title("\n".join(lines), fontsize=8)
    figure.tight_layout()
    figure.savefig(path, dpi=120)
    plt.close(figure)
    return path
