"""Command line of the timing models.

    python -m synthesis.timing train HEAVEN.bvh GUITAR.bvh … --out model.json
    python -m synthesis.timing train --holds holds.csv --transitions moves.csv --out model.json
    python -m synthesis.timing predict ELEPHANT [--model model.json]
    python -m synthesis.timing compare HEAVEN.bvh GUITAR.bvh … [--model model.json]
    python -m synthesis.timing plot HEAVEN --out heaven.png [--trajectory heaven-angles.pdf]
    python -m synthesis.timing evaluate    # the default model's leave-one-out, seed 000's beside

A recording's word is its file name's letters unless --words gives them in order.
"""

import argparse
import json
import sys
from pathlib import Path

from synthesis.fingerspelling.word_timing import TimingError
from synthesis.skeleton.bvh import BvhError
from synthesis.timing.defaults import published_model
from synthesis.timing.training import (
    HOLD_COLUMNS,
    TRANSITION_COLUMNS,
    TrainingReport,
    constant_hold_errors,
    hold_samples,
    read_annotations,
    train,
)
from synthesis.timing.transitions import DEFAULT_SPACE, METRICS, SPACES
from synthesis.timing.variable import VariableModel


def _recordings(args: argparse.Namespace) -> list:
    from synthesis.timing.recordings import Recording

    words = args.words.split(",") if args.words else [None] * len(args.recordings)
    if len(words) != len(args.recordings):
        raise TimingError(f"{len(args.recordings)} recordings but {len(words)} words.")
    return [Recording.read(path, word) for path, word in zip(args.recordings, words, strict=True)]


def _train(args: argparse.Namespace) -> int:
    if args.recordings:
        from synthesis.timing.recordings import train_on_recordings

        model, report = train_on_recordings(_recordings(args), args.metric, args.space)
    elif args.holds and args.transitions:
        holds = read_annotations(args.holds, HOLD_COLUMNS)
        transitions = read_annotations(args.transitions, TRANSITION_COLUMNS)
        source = f"{args.holds}, {args.transitions}"
        model, report = train(holds, transitions, args.metric, source=source, space=args.space)
    else:
        raise TimingError("Give recordings (BVH files) or both --holds and --transitions.")
    for line in report.lines():
        print(line)
    model.write(args.out)
    print(f"wrote {args.out}")
    return 0


def _compare(args: argparse.Namespace) -> int:
    from synthesis.timing.recordings import duration_table, format_table

    model = VariableModel.read(args.model) if args.model else published_model()
    print(format_table(duration_table(_recordings(args), model)))
    return 0


def _plot(args: argparse.Namespace) -> int:
    from synthesis.fingerspelling.spelling import spell, word_letters
    from synthesis.timing.plots import timeline_figure, trajectory_figure, write_figure
    from synthesis.timing.recordings import condition_timings

    word = "".join(word_letters(args.word))
    model = VariableModel.read(args.model) if args.model else published_model()
    timings = condition_timings(word, model)
    print(f"wrote {write_figure(timeline_figure(timings), args.out)}")
    if args.trajectory:
        motions = {name: spell(word, timing=t) for name, t in timings.items()}
        figure = trajectory_figure(motions, 60.0, word)
        print(f"wrote {write_figure(figure, args.trajectory)}")
    return 0


def _evaluate(args: argparse.Namespace) -> int:
    from synthesis.timing.bayes import LeaveOneOut
    from synthesis.timing.defaults import SIMULATED_HOLDS, model_holds, published_transitions

    samples = model_holds()
    # The default model keeps its own leave-one-out, computed when it was built.
    holds = LeaveOneOut(**published_model().metadata["leave_one_out"])
    source = f"{len(samples)} {SIMULATED_HOLDS} (the default model's training set), not recordings"
    line = "the default line: r and mean error taken from seed 000 §4.2.2, not refitted"
    report = TrainingReport(
        holds, published_transitions(), source, line, constant_ms=constant_hold_errors(samples)
    )
    for line in report.lines():
        print(line)
    if args.out:
        from synthesis.tables import write_csv, write_latex

        args.out.mkdir(parents=True, exist_ok=True)
        rows = report.rows()
        print(f"wrote {write_csv(args.out / 'leave-one-out.csv', rows)}")
        # Each figure beside what it was computed from: the default transition line is
        # seed 000's own, copied, and its input column says so (issue 53, item 5).
        columns = {
            "measure": "measure",
            "ours": "ours",
            "input": "our input",
            "published": "published",
            "published_input": "published input",
        }
        caption = "Hold leave-one-out and transition line beside seed 000 §4.2 (published)"
        print(f"wrote {write_latex(args.out / 'leave-one-out.tex', rows, columns, caption)}")
    return 0


def _curves(args: argparse.Namespace) -> int:
    import numpy as np

    from synthesis.tables import write_csv
    from synthesis.timing.defaults import SIMULATED_HOLDS, model_holds
    from synthesis.timing.learning import feature_curve, plot_curves, size_curve

    if args.holds:
        samples = hold_samples(read_annotations(args.holds, HOLD_COLUMNS))
        source = f"{len(samples)} holds of {args.holds}"
    else:
        samples = model_holds()
        source = f"{len(samples)} {SIMULATED_HOLDS}, not recordings"
    rng = np.random.default_rng(args.seed)
    points = feature_curve(samples, "all ten") + feature_curve(samples, "without shape")
    points += size_curve(samples, rng, args.repeats)
    rows = [{**p.to_dict(), "input": source} for p in points]
    for row in rows:
        published = row["published_accuracy_pct"]
        beside = f" (seed 000: {published:.2f} %)" if published != "" else ""
        accuracy = f"{row['accuracy_pct']:6.2f} %{beside}"
        print(f"{row['curve']:>14} {row['label']:>14}: {accuracy}, {row['mean_error_ms']:.2f} ms")
    args.out.mkdir(parents=True, exist_ok=True)
    print(f"wrote {write_csv(args.out / 'curves.csv', rows)}")
    title = f"Hold classifier, leave-one-out (seed 000 Figs 4.4–4.6); input: {source}"
    print(f"wrote {plot_curves(points, args.out / 'curves.png', title)}")
    return 0


def _metrics(args: argparse.Namespace) -> int:
    import numpy as np

    from synthesis.timing.training import transition_distances
    from synthesis.timing.transitions import (
        PUBLISHED_TRANSITION_R,
        PUBLISHED_TRANSITIONS_INPUT,
        TransitionModel,
    )

    transitions = read_annotations(args.transitions, TRANSITION_COLUMNS)
    times = np.array([t.duration_ms for t in transitions])
    print(f"{len(transitions)} transitions from {args.transitions} (seed 000 Fig. 4.7)")
    rows = []
    for metric in METRICS:
        distances = transition_distances(transitions, metric, args.space)
        line = TransitionModel.fit(distances, times, metric, args.space)
        print(
            f"{metric}: r = {line.r:.2f}, mean error {line.mean_abs_error_ms:.2f} ms; "
            f"published r = {PUBLISHED_TRANSITION_R[metric]:.2f}"
        )
        rows.append(
            {
                "metric": metric,
                "space": "latent" if metric == "gplvm" else args.space,
                "r": round(line.r, 3),
                "mean_error_ms": round(line.mean_abs_error_ms, 2),
                "transitions": line.nobs,
                "input": str(args.transitions),
                "published_r": PUBLISHED_TRANSITION_R[metric],
                "published_input": PUBLISHED_TRANSITIONS_INPUT,
            }
        )
    if args.out:
        from synthesis.tables import write_csv, write_latex

        args.out.mkdir(parents=True, exist_ok=True)
        print(f"wrote {write_csv(args.out / 'metrics.csv', rows)}")
        columns = {"metric": "metric", "r": "r", "mean_error_ms": "mean error (ms)"}
        columns["published_r"] = "published r"
        caption = f"Transition time regressed on each pose distance: {args.transitions}"
        print(f"wrote {write_latex(args.out / 'metrics.tex', rows, columns, caption)}")
    return 0


def _predict(args: argparse.Namespace) -> int:
    model = VariableModel.read(args.model) if args.model else published_model()
    print(json.dumps(model.timing(args.word).to_dict(), indent=2))
    return 0


def parser() -> argparse.ArgumentParser:
    """Build the command-line parser."""
    main = argparse.ArgumentParser(
        prog="python -m synthesis.timing",
        description=__doc__.split("\n\n")[0],
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    commands = main.add_subparsers(dest="command", required=True)
    fit = commands.add_parser(
        "train", help="train a Variable model from recordings or annotated CSV files"
    )
    fit.add_argument(
        "recordings",
        nargs="*",
        type=Path,
        help="recordings of words: BVH, or .pose landmarks (fitted first)",
    )
    fit.add_argument("--words", help="the recordings' words, comma-separated, in order")
    fit.add_argument("--holds", type=Path, help="CSV: word, index, hold_ms")
    fit.add_argument("--transitions", type=Path, help="CSV: word, index, transition_ms")
    fit.add_argument(
        "--metric",
        choices=METRICS,
        default="rmsd",
        help="the pose distance transitions are regressed on (seed 000 §4.2.2)",
    )
    fit.add_argument(
        "--space",
        choices=SPACES,
        default=DEFAULT_SPACE,
        help="measure pose distance over the hand's 17 joints (seed 000: 18) or its 30 DOFs",
    )
    fit.add_argument("--out", type=Path, required=True)
    fit.set_defaults(run=_train)
    compare = commands.add_parser(
        "compare", help="whole-word durations: recordings against each model (Table 4.3)"
    )
    compare.add_argument("recordings", nargs="+", type=Path)
    compare.add_argument("--words", help="the recordings' words, comma-separated, in order")
    compare.add_argument("--model", type=Path)
    compare.set_defaults(run=_compare)
    plot = commands.add_parser(
        "plot", help="draw a word's timeline under each condition (PNG or PDF)"
    )
    plot.add_argument("word")
    plot.add_argument("--out", type=Path, required=True, help="the timeline figure")
    plot.add_argument("--trajectory", type=Path, help="also the average joint-angle figure")
    plot.add_argument("--model", type=Path)
    plot.set_defaults(run=_plot)
    evaluate = commands.add_parser(
        "evaluate", help="the default model's leave-one-out, beside seed 000 §4.2's"
    )
    evaluate.add_argument(
        "--out",
        type=Path,
        help="a directory for leave-one-out.csv and .tex (ours beside seed 000's)",
    )
    evaluate.set_defaults(run=_evaluate)
    curves = commands.add_parser(
        "curves",
        help="hold accuracy by feature and by training-set size (Figs 4.4–4.6)",
    )
    curves.add_argument(
        "--holds",
        type=Path,
        help="annotated holds (word,index,hold_ms); default: the "
        "built-in model's 384 simulated holds",
    )
    curves.add_argument("--repeats", type=int, default=20, help="random subsets per size")
    curves.add_argument("--seed", type=int, default=0)
    curves.add_argument("--out", type=Path, required=True)
    curves.set_defaults(run=_curves)
    metrics = commands.add_parser(
        "metrics", help="each pose distance's regression on annotated transitions (Fig. 4.7)"
    )
    metrics.add_argument("--transitions", type=Path, required=True)
    metrics.add_argument("--space", choices=SPACES, default=DEFAULT_SPACE)
    metrics.add_argument("--out", type=Path, help="a directory for metrics.csv and .tex")
    metrics.set_defaults(run=_metrics)
    predict = commands.add_parser("predict", help="print a word's Variable timing as JSON")
    predict.add_argument("word")
    predict.add_argument("--model", type=Path)
    predict.set_defaults(run=_predict)
    return main


def main(argv: list[str] | None = None) -> int:
    """Run the command line; bad input prints one error line and returns 2."""
    args = parser().parse_args(argv)
    try:
        return args.run(args)
    except (TimingError, BvhError, ValueError, OSError) as error:
        print(f"error: {error}", file=sys.stderr)
        return 2
