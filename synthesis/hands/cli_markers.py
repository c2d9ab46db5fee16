"""The ``markers`` command of ``python -m synthesis.hands``: seed 000 Table 3.1.

    python -m synthesis.hands markers --out dir/                          # the engine's setup
    python -m synthesis.hands markers --configuration paper --out dir/    # seed 000 §3.1's
    python -m synthesis.hands markers --configuration paper --database poses.npz \
        --selection selection.bvh --test test.bvh --out dir/              # your own capture

Every row printed and written (``table-3-1.csv``, ``table-3-1.tex``) carries its
configuration, its input and the published figure with the published input.
"""

import argparse
from pathlib import Path

TABLE_3_1_COLUMNS = {
    "configuration": "configuration",
    "input": "input",
    "poses": "p",
    "markers": "m",
    "set": "markers",
    "error_cm": "error (cm)",
    "sd_cm": "s.d.",
    "published_cm": "published (cm)",
    "published_sd_cm": "pub. s.d.",
}


def _print_table(rows: list[dict]) -> None:
    for row in rows:
        published = (
            f"published {row['published_cm']} cm (s.d. {row['published_sd_cm']})"
            if row["published_cm"] is not None
            else "not published"
        )
        print(
            f"p = {row['poses']:4d}, m = {row['markers']:2d}: {row['error_cm']:.2f} cm "
            f"(s.d. {row['sd_cm']:.2f}); {published} [{row['set']}]"
        )


def _engine_inputs(args: argparse.Namespace):
    """Return the engine configuration's test motion (the words spelled) and database."""
    import numpy as np

    from synthesis.fingerspelling.spelling import spell
    from synthesis.hands.handover import builtin_pose_database

    test = np.vstack([spell(word, args.side, 120.0) for word in args.words])
    return test, builtin_pose_database(args.side)


def _engine_table(args: argparse.Namespace, hand, test, database) -> list[dict]:
    import numpy as np

    from synthesis.hands.evaluation import ENGINE_CONFIGURATION, table_3_1

    source = f"the engine's spelling of {', '.join(args.words)} from {database.source}"
    print(f"{ENGINE_CONFIGURATION}\n  input: {source}")
    rows = table_3_1(
        database,
        hand,
        test,
        120.0,
        np.random.default_rng(args.seed),
        source,
        tuple(args.poses),
        tuple(args.sizes),
    )
    _print_table(rows)
    return rows


def _paper_tables(args: argparse.Namespace, hand) -> list[dict]:
    import numpy as np

    from synthesis.hands.evaluation import PAPER_CONFIGURATION, PUBLISHED_INPUT, paper_table_3_1
    from synthesis.hands.heldout import human_letters, simulated_gestures

    rows = []
    inputs = ["own"] if args.database else args.paper_input
    for name in inputs:
        if name == "own":
            held_out = _own_held_out(args)
        elif name == "gestures":
            rng = np.random.default_rng(args.seed)
            seconds = args.gesture_seconds
            held_out = simulated_gestures(args.side, rng, seconds, seconds / 9, seconds / 4.5)
        else:
            held_out = human_letters(args.side)
        print(f"{PAPER_CONFIGURATION}\n  input: {held_out.input}\n  published: {PUBLISHED_INPUT}")
        table = paper_table_3_1(
            held_out,
            hand,
            120.0,
            np.random.default_rng(args.seed),
            tuple(args.poses),
            tuple(args.sizes),
            args.select_on,
        )
        _print_table(table)
        rows += table
    return rows


def _own_held_out(args: argparse.Namespace):
    """Return the researcher's own database with their selection and test motions."""
    from synthesis.hands.heldout import HeldOut
    from synthesis.hands.posedb import recorded_dofs
    from synthesis.hands.reconstruct import PoseDatabase

    if not (args.selection and args.test):
        raise ValueError("--database needs --selection and --test motions withheld from it.")

    def names(paths) -> str:
        return ", ".join(Path(path).name for path in paths)

    database = PoseDatabase.read(args.database)
    return HeldOut(
        database,
        recorded_dofs(args.selection, args.side),
        recorded_dofs(args.test, args.side),
        f"{database.source}; markers chosen on {names(args.selection)}, tested on "
        f"{names(args.test)}",
    )


def _markers(args: argparse.Namespace) -> int:
    import numpy as np

    from synthesis.hands.evaluation import compare_marker_choices
    from synthesis.rigs.hand import HandModel
    from synthesis.tables import write_csv, write_latex

    hand = HandModel(args.side)
    engine = args.configuration in ("engine", "both")
    test, database = _engine_inputs(args) if engine else (None, None)
    rows = _engine_table(args, hand, test, database) if engine else []
    if args.configuration in ("paper", "both"):
        rows += _paper_tables(args, hand)
    args.out.mkdir(parents=True, exist_ok=True)
    print(f"wrote {write_csv(args.out / 'table-3-1.csv', rows)}")
    caption = (
        "Mean marker error (cm) of the nearest-pose reconstruction by database size p and "
        "marker count m, beside seed 000 Table 3.1 (published)"
    )
    print(f"wrote {write_latex(args.out / 'table-3-1.tex', rows, TABLE_3_1_COLUMNS, caption)}")
    if engine and args.compare:
        choices = compare_marker_choices(database, hand, test, np.random.default_rng(args.seed))
        for row in choices:
            print(f"m = {row['markers']}, {row['method']}: {row['set']} — {row['error_cm']:.2f} cm")
        print(f"wrote {write_csv(args.out / 'marker-sets.csv', choices)}")
        _six_markers(args, hand, test, database)
    return 0


def _six_markers(args: argparse.Namespace, hand, test, database) -> None:
    """Write seed 000 Fig. 3.5's comparison: three six-marker sets rebuilt by LWR."""
    import numpy as np

    from synthesis.hands.six_markers import plot_six_marker_sets, six_marker_sets
    from synthesis.tables import write_csv

    found = six_marker_sets(database, hand, test, 120.0, np.random.default_rng(args.seed))
    source = f"the engine's spelling of {', '.join(args.words)} from {database.source}"
    rows = [{**entry.to_dict(), "input": source} for entry in found]
    for row in rows:
        figures = f"{row['marker_error_cm']:.2f} cm, {row['angle_error_deg']:.2f}° per DOF"
        print(f"m = 6, {row['method']}: {row['set']} — {figures}")
    print(f"wrote {write_csv(args.out / 'six-markers.csv', rows)}")
    title = f"Six-marker sets rebuilt by LWR (seed 000 Fig. 3.5): {source}"
    print(f"wrote {plot_six_marker_sets(found, 120.0, args.out / 'six-markers.png', title)}")


def add_markers_command(commands) -> None:
    """Add the ``markers`` command to the hands command line's subparsers."""
    markers = commands.add_parser("markers", help="Table 3.1 and the marker-set choices")
    markers.add_argument("--out", type=Path, required=True)
    markers.add_argument(
        "--configuration",
        choices=("engine", "paper", "both"),
        default="engine",
        help="engine: PCA-ranked markers at the wrist on spelled words; paper: seed 000 "
        "§3.1's Alg. 1 markers at the forearm on held-out motion",
    )
    markers.add_argument(
        "--words", nargs="+", default=["GIRL", "WALK", "HELLO"], help="the engine's test words"
    )
    markers.add_argument(
        "--paper-input",
        nargs="+",
        choices=("gestures", "letters"),
        default=["gestures", "letters"],
        help="the paper configuration's inputs: simulated gestures, the human letters",
    )
    markers.add_argument(
        "--database",
        type=Path,
        help="the paper configuration on your own pose database (python -m synthesis.hands "
        "database --root forearm) instead of the built-in inputs",
    )
    markers.add_argument(
        "--selection", nargs="+", type=Path, help="motions withheld to choose markers on"
    )
    markers.add_argument("--test", nargs="+", type=Path, help="motions withheld to test on")
    markers.add_argument(
        "--gesture-seconds",
        type=float,
        default=90.0,
        help="seconds of simulated gestures in the database (selection and test: 1/9, 2/9)",
    )
    markers.add_argument(
        "--select-on",
        choices=("selection", "test"),
        default="selection",
        help="choose Alg. 1's markers on a withheld selection sequence, or on the test one",
    )
    markers.add_argument("--poses", nargs="+", type=int, default=[50, 100, 500, 1000])
    markers.add_argument("--sizes", nargs="+", type=int, default=[2, 4, 6])
    markers.add_argument(
        "--no-compare",
        dest="compare",
        action="store_false",
        help="skip the engine's PCA against exhaustive-search comparison",
    )
    markers.add_argument("--side", choices=("right", "left"), default="right")
    markers.add_argument("--seed", type=int, default=0)
    markers.set_defaults(run=_markers)
