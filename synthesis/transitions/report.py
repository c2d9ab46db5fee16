"""Write a transition evaluation as CSV, LaTeX and PNG (seed 001 Table 5.1, Fig. 4.4)."""

from pathlib import Path

import numpy as np

from synthesis.tables import write_csv
from synthesis.transitions.curves import SEED_NAMES
from synthesis.transitions.database import TransitionDatabase
from synthesis.transitions.datadriven import BASELINES, MODEL_LABELS, MODELS, baseline, fit_entry
from synthesis.transitions.evaluate import (
    PUBLISHED_INPUT,
    PUBLISHED_RMSE_DEG,
    Evaluation,
    evaluation_input,
    summary_rows,
    verdict,
)

SIMULATED = " (simulated captures)"


def latex_table(evaluation: Evaluation) -> str:
    """Return Table 5.1's layout as a LaTeX tabular: RMSE per curve type, mean, best-in."""
    rows = summary_rows(evaluation)
    label = SIMULATED if evaluation.simulated else ""
    lines = [
        "\\begin{table}",
        "\\centering",
        f"\\caption{{Transition RMSE in degrees by model and curve{label}; "
        f"ours: {evaluation_input(evaluation)}, leave-one-out, search "
        f"{evaluation.weighting}. Published: seed 001 Table 5.1, {PUBLISHED_INPUT}.}}",
        "\\begin{tabular}{l" + "r" * (len(SEED_NAMES) + 4) + "}",
        "\\hline",
        "Model & " + " & ".join(SEED_NAMES) + " & Mean & Best in & Published & Pub. best \\\\",
        "\\hline",
    ]
    for row in rows:
        cells = [row["model"]] + [f"{row[n]:.2f}" for n in SEED_NAMES]
        cells += [
            f"{row['mean_rmse_deg']:.2f}",
            str(row["best_in"]),
            f"{row['published_rmse_deg']:.2f}",
            str(row["published_best_in"]),
        ]
        lines.append(" & ".join(cells) + " \\\\")
    lines += ["\\hline", "\\end{tabular}", "\\end{table}", ""]
    return "\n".join(lines)


def _plot_means(evaluation: Evaluation, path: Path) -> Path:
    from synthesis.plotting import pyplot

    plt = pyplot()

    means = evaluation.mean_by_model
    x = np.arange(len(MODELS))
    figure, axes = plt.subplots(figsize=(6.4, 3.6))
    here = "this database" + (SIMULATED if evaluation.simulated else "")
    axes.bar(x - 0.2, [means[m] for m in MODELS], 0.4, label=here)
    axes.bar(x + 0.2, [PUBLISHED_RMSE_DEG[m] for m in MODELS], 0.4, label="seed 001 Table 5.1")
    axes.set_xticks(x, [MODEL_LABELS[m] for m in MODELS], fontsize=8)
    axes.set_ylabel("mean RMSE (degrees)")
    axes.set_title(
        "Transition models: RMSE against the recording"
        + (SIMULATED if evaluation.simulated else ""),
        fontsize=10,
    )
    axes.legend(fontsize=8)
    figure.tight_layout()
    figure.savefig(path, dpi=120)
    plt.close(figure)
    return path


def plot_transition(
    database: TransitionDatabase, index: int, evaluation: Evaluation, path: Path
) -> Path:
    """Plot one transition's seven curves: recording vs each model (seed 001 Fig. 4.4).

    The data-driven models fit the stored transition *evaluation* matched to it.
    """
    from synthesis.plotting import pyplot

    plt = pyplot()

    entry = database.entries[index]
    matched = next(e for e in database.entries if e.id == evaluation.matches[index])
    n = entry.gap_frames
    frames = np.arange(-len(entry.before) + 1, n + 1 + len(entry.after))
    recorded = np.degrees(np.vstack([entry.before, entry.values[1:-1], entry.after]))
    figure, axes = plt.subplots(2, 4, figsize=(12, 5.2), sharex=True)
    for model in MODELS:
        if model in BASELINES:
            synthesized = baseline(model, entry.before, entry.after, n)
        else:
            synthesized = fit_entry(matched, entry.before, entry.after, n, model)
        for c, ax in enumerate(axes.flat[:7]):
            ax.plot(
                np.arange(1, n + 1), np.degrees(synthesized[:, c]), label=MODEL_LABELS[model], lw=1
            )
    for c, ax in enumerate(axes.flat[:7]):
        ax.plot(frames, recorded[:, c], color="black", lw=1.8, label="recorded", zorder=0)
        ax.axvspan(1, n, color="#fff3b0", zorder=-1)
        ax.set_title(SEED_NAMES[c], fontsize=9)
        ax.tick_params(labelsize=7)
    axes.flat[7].axis("off")
    axes.flat[7].legend(*axes.flat[0].get_legend_handles_labels(), fontsize=8, loc="center")
    figure.suptitle(
        f"Transition {entry.id} ({entry.labels[0]} → {entry.labels[1]}), degrees"
        + (SIMULATED if entry.simulated else ""),
        fontsize=10,
    )
    figure.tight_layout()
    figure.savefig(path, dpi=100)
    plt.close(figure)
    return path


def write_evaluation(
    database: TransitionDatabase,
    evaluations: dict[str, Evaluation],
    directory: str | Path,
    weighting: str,
    plots: int = 3,
) -> list[Path]:
    """Write every output of an evaluation to *directory*; return the files written.

    *evaluations* by weighting; *weighting*'s is the one tabulated and plotted, and
    ``weightings.csv`` compares them all (which search wins).
    """
    directory = Path(directory)
    directory.mkdir(parents=True, exist_ok=True)
    main = evaluations[weighting]
    written = [write_csv(directory / "table.csv", summary_rows(main))]
    rows = [
        {
            "transition": tid,
            "signer": signer,
            "model": MODEL_LABELS[m],
            "curve": name,
            "rmse_deg": round(float(main.rmse_deg[t, i, c]), 4),
            "matched": match,
            "simulated": main.simulated,
        }
        for t, (tid, signer, match) in enumerate(
            zip(main.ids, main.signers, main.matches, strict=True)
        )
        for i, m in enumerate(main.models)
        for c, name in enumerate(SEED_NAMES)
    ]
    written.append(write_csv(directory / "transitions.csv", rows))
    written.append(
        write_csv(
            directory / "weightings.csv",
            [
                {
                    "weighting": w,
                    "hermite_rmse_deg": round(e.mean_by_model["hermite"], 3),
                    "bspline_rmse_deg": round(e.mean_by_model["bspline"], 3),
                    "same_signer_share": round(e.same_signer_share, 3),
                    "same_transition_share": round(e.same_transition_share, 3),
                    "simulated": e.simulated,
                }
                for w, e in evaluations.items()
            ],
        )
    )
    tex = directory / "table.tex"
    tex.write_text(latex_table(main), "utf-8")
    text = directory / "verdict.txt"
    text.write_text(verdict(main) + "\n", "utf-8")
    written += [tex, text, _plot_means(main, directory / "rmse.png")]
    for index in range(min(plots, len(database.entries))):
        entry = database.entries[index]
        written.append(plot_transition(database, index, main, directory / f"curves-{entry.id}.png"))
    return written


def plot_speed(
    text: str, path: str | Path, models=("keyed", "blended", "hermite"), rate_hz: float = 60.0
) -> Path:
    """Plot the dominant arm's angular speed over a sentence under each transition model.

    Seed 004's blending is C⁰ only: its speed jumps where an overlap starts and ends,
    which this plot shows beside the smooth models (with the velocity jumps' peak).
    """
    from synthesis.plotting import pyplot

    plt = pyplot()

    from synthesis.signing.sentence import SentenceOptions, synthesize
    from synthesis.transitions.blending import velocity_jumps
    from synthesis.transitions.builtin import database_search
    from synthesis.transitions.curves import arm_columns
    from synthesis.transitions.sentence import blend_sentence, retransition

    options = SentenceOptions(rate_hz=rate_hz, liveliness=None)
    sentence = synthesize(text, options)
    figure, axes = plt.subplots(figsize=(8, 3.4))
    for model in models:
        if model == "keyed":
            dofs = sentence.dofs_rad
        elif model == "blended":
            dofs = blend_sentence(text, options)[0]
        else:
            search = database_search() if model in ("hermite", "bspline") else None
            dofs = retransition(sentence, model, search)
        arm = np.asarray(dofs)[:, arm_columns(sentence.body.dof_names, "right")]
        speed = np.degrees(np.linalg.norm(np.diff(arm, axis=0), axis=1) * rate_hz)
        jump = np.degrees(velocity_jumps(arm, rate_hz)).max()
        axes.plot(
            np.arange(len(speed)) / rate_hz,
            speed,
            lw=1,
            label=f"{model} (largest velocity jump {jump:.0f}°/s per frame)",
        )
    axes.set_xlabel("time (s)")
    axes.set_ylabel("right arm speed (°/s)")
    axes.set_title(f"Arm speed: {text}", fontsize=10)
    axes.legend(fontsize=8)
    figure.tight_layout()
    figure.savefig(path, dpi=110)
    plt.close(figure)
    return Path(path)
