"""Command line: ``python -m analysis report responses.csv --out DIR`` and ``import-wide``."""

import argparse
import sys
import time
from pathlib import Path

from analysis.exclusions import ExclusionRules, apply_exclusions
from analysis.outputs import write_report
from analysis.report import ReportOptions, build_report
from analysis.tidy import TidyFormatError, read_json_file, read_responses
from analysis.within import CORRECTIONS


def _keep_only(values: list[str]) -> dict[str, tuple[str, ...]]:
    filters = {}
    for value in values:
        column, _, allowed = value.partition("=")
        if not column or not allowed:
            raise TidyFormatError(f"--only needs COLUMN=VALUE[,VALUE…], got {value!r}.")
        filters[column] = tuple(v.strip() for v in allowed.split(","))
    return filters


def _report(args: argparse.Namespace) -> int:
    started = time.perf_counter()
    frame = read_responses(args.csv)
    options = ReportOptions(
        conditions=tuple(args.conditions.split(",")) if args.conditions else None,
        tie_handling=args.ties,
        correction=args.correction,
        comparative_points=args.comparative_points,
        exclusions=ExclusionRules(
            pilot=not args.keep_pilot,
            failed_attention=not args.keep_failed_attention,
            incomplete=not args.keep_incomplete,
            keep_only=_keep_only(args.only),
            answered_before_end=args.exclude_early_answers,
            min_median_page_s=args.min_median_page_s,
        ),
    )
    report = build_report(frame, options, source=Path(args.csv).name, title=args.title)
    kept, _ = apply_exclusions(frame, options.exclusions)
    written = write_report(report, kept, args.out, draw_figures=not args.no_figures)
    print(
        f"Wrote {len(written)} files to {args.out} "
        f"({report.exclusions.participants_included} participants, "
        f"{time.perf_counter() - started:.1f} s)."
    )
    if report.pairwise is not None and report.pairwise.rm_anova is not None:
        print(f"Repeated-measures ANOVA: {report.pairwise.rm_anova.apa()}")
    return 0


def _import_wide(args: argparse.Namespace) -> int:
    import pandas as pd

    from analysis.wide import read_mapping, wide_to_tidy

    mapping = read_mapping(args.mapping)
    header = list(range(mapping.header_rows)) if mapping.header_rows > 1 else 0
    try:
        wide = pd.read_csv(args.csv, dtype=str, keep_default_na=False, header=header)
    except FileNotFoundError:
        raise TidyFormatError(f"{args.csv}: no such file.") from None
    tidy = wide_to_tidy(wide, mapping, source=Path(args.csv).name)
    tidy.to_csv(args.out, index=False)
    participants = tidy["participant"].nunique()
    print(f"Wrote {len(tidy)} tidy rows for {participants} participants to {args.out}.")
    return 0


def _sizes(text: str) -> list[int]:
    """Parse N as "10:60:5" (start:stop:step, stop included) or "10,20,40"."""
    try:
        if ":" in text:
            start, stop, step = (int(part) for part in text.split(":"))
            if step <= 0:
                raise ValueError
            return list(range(start, stop + 1, step))
        return [int(part) for part in text.split(",")]
    except ValueError:
        raise TidyFormatError(f"--n takes START:STOP:STEP or N1,N2,…, got {text!r}.") from None


def _power(args: argparse.Namespace) -> int:
    from analysis.power import design_from_responses, power_curve, read_design
    from analysis.power.plan import effects_for, write_power

    frame = read_responses(args.csv)
    kept, _ = apply_exclusions(frame, ExclusionRules(pilot=False))
    design = (
        read_design(args.design)
        if args.design
        else design_from_responses(kept, args.kind, args.question or "")
    )
    stated = read_json_file(args.effects) if args.effects else None
    effects = effects_for(kept, design, stated, source=Path(args.csv).name)
    curve = power_curve(
        design,
        effects,
        _sizes(args.n),
        simulations=args.simulations,
        alpha=args.alpha,
        seed=args.seed,
        correction=args.correction,
        workers=args.workers,
    )
    print(curve.summary())
    if args.out:
        written = write_power(curve, args.out)
        print(f"Wrote {', '.join(written)} to {args.out}.")
    return 0


def parser() -> argparse.ArgumentParser:
    """Build the command-line parser."""
    main = argparse.ArgumentParser(prog="python -m analysis", description=__doc__)
    commands = main.add_subparsers(dest="command", required=True)

    report = commands.add_parser("report", help="analyse a tidy CSV and write a report")
    report.add_argument("csv", help="tidy responses (docs/tidy-format.md)")
    report.add_argument("--out", required=True, help="output folder")
    report.add_argument("--conditions", help="condition order, comma-separated")
    report.add_argument("--title", default="", help="the study's title, heading the report")
    report.add_argument("--ties", choices=("exclude", "split"), default="exclude")
    report.add_argument("--correction", choices=tuple(CORRECTIONS), default="holm")
    report.add_argument("--comparative-points", type=int, default=5)
    report.add_argument("--keep-pilot", action="store_true")
    report.add_argument("--keep-failed-attention", action="store_true")
    report.add_argument("--keep-incomplete", action="store_true")
    report.add_argument(
        "--only",
        action="append",
        default=[],
        metavar="COLUMN=V1,V2",
        help="keep only participants whose COLUMN is one of the values (repeatable)",
    )
    report.add_argument(
        "--exclude-early-answers",
        action="store_true",
        help="exclude participants who answered a page before its clips had ended",
    )
    report.add_argument(
        "--min-median-page-s",
        type=float,
        metavar="S",
        help="exclude participants whose median time on a page is under S seconds",
    )
    report.add_argument("--no-figures", action="store_true")
    report.set_defaults(run=_report)

    power = commands.add_parser(
        "power", help="simulate the planned design's power over a range of N (SIMULATED)"
    )
    power.add_argument("csv", help="pilot responses in the tidy format (pilot rows are kept)")
    power.add_argument("--design", help="design.json (default: the pilot participants' trials)")
    power.add_argument("--kind", choices=("pairwise", "rating"), default="pairwise")
    power.add_argument("--question", help="the rated question (with --kind rating)")
    power.add_argument("--effects", help="stated effects JSON instead of the pilot's estimates")
    power.add_argument("--n", default="10:60:5", help="participants: START:STOP:STEP or N1,N2")
    power.add_argument("--simulations", type=int, default=200)
    power.add_argument("--alpha", type=float, default=0.05)
    power.add_argument("--seed", type=int, default=1)
    power.add_argument("--correction", choices=tuple(CORRECTIONS), default="holm")
    power.add_argument("--workers", type=int, default=None, help="processes (default: cores)")
    power.add_argument("--out", help="folder for power.csv, power.json and power.png")
    power.set_defaults(run=_power)

    wide = commands.add_parser("import-wide", help="turn a survey export into the tidy format")
    wide.add_argument("csv", help="wide CSV (one row per participant)")
    wide.add_argument("--mapping", required=True, help="JSON column mapping (docs/tidy-format.md)")
    wide.add_argument("--out", required=True, help="tidy CSV to write")
    wide.set_defaults(run=_import_wide)
    return main


def main(argv: list[str] | None = None) -> int:
    """Run the command line; bad input prints one error line and returns 2."""
    args = parser().parse_args(argv)
    try:
        return args.run(args)
    except (TidyFormatError, ValueError) as error:
        print(f"error: {error}", file=sys.stderr)
        return 2
