"""Command line of the inter-sign transitions.

    python -m synthesis.transitions simulate --out captures/ [--signers 4 --sentences 6]
    python -m synthesis.transitions build captures/*.bvh … --out db.json
    python -m synthesis.transitions evaluate db.json --out results/ [--weighting raw]
    python -m synthesis.transitions speed "BUT SURPRISE MY BROTHER" --out speed.png
    python -m synthesis.transitions lexicon HELLO.bvh THANKS.pose … --out lexicon.json
    python -m synthesis.transitions lexicon --simulate WHERE SURPRISE --out signs/

A recording is a BVH of the engine's body or a captured .pose file, with its
segmentation beside it (NAME.segments.json or NAME.segments.xml; seed 001 §5.2.1).
"""

import argparse
import sys
from pathlib import Path

from synthesis.transitions.database import DatabaseError, TransitionDatabase, build_database
from synthesis.transitions.evaluate import HOLDOUTS
from synthesis.transitions.lexicon import LexiconError
from synthesis.transitions.recording import RecordingError, read_recording, write_recording
from synthesis.transitions.search import WEIGHTINGS
from synthesis.transitions.segments import SegmentationError


def _simulate(args: argparse.Namespace) -> int:
    from synthesis.transitions.simulate import simulated_captures

    recordings = simulated_captures(args.signers, args.sentences, args.seed)
    for recording in recordings:
        write_recording(recording, args.out)
    print(f"wrote {len(recordings)} simulated captures (BVH + segments.json) to {args.out}")
    return 0


def _build(args: argparse.Namespace) -> int:
    recordings = [read_recording(path) for path in args.recordings]
    database = build_database(
        recordings, args.min_range_deg, tuple(Path(p).name for p in args.recordings)
    )
    database.write(args.out)
    label = " (simulated captures)" if database.simulated else ""
    print(
        f"wrote {args.out}: {len(database.entries)} transitions from "
        f"{len(recordings)} recordings{label}"
    )
    return 0


def _evaluate(args: argparse.Namespace) -> int:
    from synthesis.transitions.evaluate import compare_weightings, summary_rows, verdict
    from synthesis.transitions.report import write_evaluation

    database = TransitionDatabase.read(args.database)
    evaluations = compare_weightings(database, args.holdout)
    main = evaluations[args.weighting]
    names = list(summary_rows(main)[0])
    print("\t".join(names))
    for row in summary_rows(main):
        print("\t".join(str(row[n]) for n in names))
    for weighting, evaluation in evaluations.items():
        means = evaluation.mean_by_model
        print(
            f"search {weighting}: Hermite {means['hermite']:.2f}°, B-spline {means['bspline']:.2f}°"
        )
    best = min(evaluations, key=lambda w: evaluations[w].mean_by_model["hermite"])
    print(f"best search for the data-driven Hermite: {best}")
    print(verdict(main))
    for path in write_evaluation(database, evaluations, args.out, args.weighting):
        print(f"wrote {path}")
    return 0


def _speed(args: argparse.Namespace) -> int:
    from synthesis.transitions.report import plot_speed

    print(f"wrote {plot_speed(args.text, args.out, tuple(args.models.split(',')))}")
    return 0


def _lexicon(args: argparse.Namespace) -> int:
    from synthesis.transitions.lexicon import simulated_lexicon, write_lexicon

    if args.simulate:
        path = simulated_lexicon(args.items, args.out, attack_ms=args.attack_ms)
        print(f"wrote {path}: {len(args.items)} simulated recorded signs")
        return 0
    path = write_lexicon(args.items, args.out)
    print(f"wrote {path}: {len(args.items)} recorded signs")
    return 0


def parser() -> argparse.ArgumentParser:
    """Return the argument parser of ``python -m synthesis.transitions``."""
    root = argparse.ArgumentParser(
        prog="python -m synthesis.transitions", description=__doc__.split("\n\n")[0]
    )
    commands = root.add_subparsers(dest="command", required=True)
    simulate = commands.add_parser("simulate", help="write simulated captures with segments")
    simulate.add_argument("--out", type=Path, required=True)
    simulate.add_argument("--signers", type=int, default=4)
    simulate.add_argument("--sentences", type=int, default=6)
    simulate.add_argument("--seed", type=int, default=0)
    simulate.set_defaults(run=_simulate)
    build = commands.add_parser("build", help="build a transition database from recordings")
    build.add_argument("recordings", nargs="+", type=Path)
    build.add_argument("--out", type=Path, required=True)
    build.add_argument(
        "--min-range-deg",
        type=float,
        default=5.0,
        help="leave out an arm that moves less than this (a resting arm)",
    )
    build.set_defaults(run=_build)
    evaluate = commands.add_parser("evaluate", help="Table 5.1: RMSE of every model")
    evaluate.add_argument("database", type=Path)
    evaluate.add_argument("--out", type=Path, required=True)
    evaluate.add_argument("--weighting", choices=WEIGHTINGS, default="raw")
    evaluate.add_argument(
        "--holdout",
        choices=HOLDOUTS,
        default="transition",
        help="leave out the query's own transition (seed 001), or every recording of the "
        "same sign pair by any signer",
    )
    evaluate.set_defaults(run=_evaluate)
    speed = commands.add_parser("speed", help="plot a sentence's arm speed per transition model")
    speed.add_argument("text")
    speed.add_argument("--out", type=Path, required=True)
    speed.add_argument("--models", default="keyed,blended,hermite")
    speed.set_defaults(run=_speed)
    lexicon = commands.add_parser("lexicon", help="write a lexicon of recorded signs")
    lexicon.add_argument("items", nargs="+", help="recordings (or glosses with --simulate)")
    lexicon.add_argument(
        "--out", type=Path, required=True, help="the manifest (a directory with --simulate)"
    )
    lexicon.add_argument(
        "--simulate", action="store_true", help="record the engine's signs as simulated recordings"
    )
    lexicon.add_argument(
        "--attack-ms",
        type=float,
        default=0.0,
        help="with --simulate: hold the rest until each attack and decay lasts this long "
        "(seed 004: 1000, for its 1 s blend overlap)",
    )
    lexicon.set_defaults(run=_lexicon)
    return root


def main(argv: list[str] | None = None) -> int:
    """Run the command line; return its exit status (2 with a message on bad input)."""
    args = parser().parse_args(argv)
    try:
        return args.run(args)
    except (RecordingError, SegmentationError, DatabaseError, LexiconError, ValueError) as error:
        print(f"error: {error}", file=sys.stderr)
        return 2
