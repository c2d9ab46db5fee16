"""Command line of the timing models.

python -m synthesis.timing train --holds holds.csv --transitions moves.csv --out model.json
python -m synthesis.timing predict ELEPHANT [--model model.json]
"""

import argparse
import json
import sys
from pathlib import Path

from synthesis.timing.defaults import published_model
from synthesis.timing.training import (
    HOLD_COLUMNS,
    TRANSITION_COLUMNS,
    read_annotations,
    train,
)
from synthesis.timing.variable import VariableModel
from synthesis.timing.word import TimingError


def _train(args: argparse.Namespace) -> int:
    holds = read_annotations(args.holds, HOLD_COLUMNS)
    transitions = read_annotations(args.transitions, TRANSITION_COLUMNS)
    model, report = train(
        holds, transitions, args.metric, source=f"{args.holds}, {args.transitions}"
    )
    for line in report.lines():
        print(line)
    model.save(args.out)
    print(f"wrote {args.out}")
    return 0


def _predict(args: argparse.Namespace) -> int:
    model = VariableModel.load(args.model) if args.model else published_model()
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
    fit = commands.add_parser("train", help="train a Variable model from annotated CSV files")
    fit.add_argument("--holds", type=Path, required=True, help="CSV: word, index, hold_ms")
    fit.add_argument("--transitions", type=Path, required=True,
                     help="CSV: word, index, transition_ms")  # fmt: skip
    fit.add_argument("--metric", choices=("rmsd", "manhattan", "chebyshev"), default="rmsd")
    fit.add_argument("--out", type=Path, required=True)
    fit.set_defaults(run=_train)
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
    except (TimingError, ValueError, OSError) as error:
        print(f"error: {error}", file=sys.stderr)
        return 2
