"""Command line of hand dimensionality.

    python -m synthesis.hands reduce motion.bvh --range-deg 5 --rmsd 0.5 \
        --out reduced.bvh --report dir/
    python -m synthesis.hands reduce --spell HEAVEN --out reduced.bvh --report dir/
    python -m synthesis.hands reconstruct --spell HEAVEN --markers 3 --method lwr \
        --out rebuilt.bvh --report dir/
    python -m synthesis.hands markers --out dir/   # Table 3.1 and Alg. 1 vs Alg. 2
    python -m synthesis.hands markers --configuration paper --out dir/   # seed 000's setup
    python -m synthesis.hands database [RECORDINGS…] --words CAT DOG --simulated 2 --out poses.npz

A motion is a BVH of the engine's hand or body, or a captured .pose file; --spell uses
the engine's own fingerspelling of a word (at 30 fps, both as the seed analysed).
"""

import argparse
import sys
from pathlib import Path

from synthesis.hands.cli_markers import add_markers_command
from synthesis.hands.markers import ROOTS
from synthesis.hands.motion import HandMotionError, from_dofs, read_hand_motion, reduce_motion
from synthesis.hands.reconstruct import LWR_VARIANCE


def _motion(args: argparse.Namespace, rate_hz: float):
    """Return the motion the command works on and what it is, in words."""
    letters = getattr(args, "human_letters", "")
    if sum(map(bool, (args.motion, args.spell, letters))) != 1:
        raise HandMotionError(
            "Give a motion file, --spell WORD or --human-letters LETTERS (one of them)."
        )
    if args.motion:
        return read_hand_motion(args.motion, args.side), str(args.motion)
    if letters:
        from synthesis.hands.posedb import RATE_HZ, human_letter_poses
        from synthesis.rigs.hand import HandModel
        from synthesis.skeleton.retime import resample_curves

        letters = "".join(dict.fromkeys(letters.upper()))
        dofs = resample_curves(human_letter_poses(args.side, letters), RATE_HZ, rate_hz)
        return (
            from_dofs(HandModel(args.side), dofs, rate_hz),
            f"human letters {letters} (spoken-to-signed), one after another at {rate_hz:g} Hz",
        )
    from synthesis.fingerspelling.spelling import spell
    from synthesis.rigs.hand import HandModel

    spelled = spell(args.spell, args.side, rate_hz)
    return (
        from_dofs(HandModel(args.side), spelled, rate_hz),
        f"the engine's spelling of {args.spell} at {rate_hz:g} Hz",
    )


def _reduce(args: argparse.Namespace) -> int:
    from synthesis.hands.report import write_reduction_report
    from synthesis.skeleton.bvh import write_bvh

    motion, source = _motion(args, 30.0)
    reduced, reduction = reduce_motion(motion, args.range_deg, args.rmsd)
    print(
        f"{source}: {reduction.dof_count} of {len(motion.names)} DOFs free "
        f"({len(reduction.constant)} constant, {len(reduction.relations)} rebuilt)"
    )
    for relation in reduction.relations:
        print(
            f"  {relation.dependent} ← {relation.controller} "
            f"({relation.metric} = {relation.rmsd:.2f})"
        )
    from synthesis.hands.report import PUBLISHED_REDUCTION_INPUT, step_rows

    curves = motion.analysis_curves_deg()
    steps = step_rows(curves, motion.names, source)
    print(f"seed 002's steps on {source} (published: {PUBLISHED_REDUCTION_INPUT}):")
    for row in steps:
        print(
            f"  {row['step']}: {row['dofs']} of {row['of']} DOFs, mean error "
            f"{row['mean_error_deg']:.2f}°; published {row['published_dofs_of_50']} of 50"
        )
    if args.out:
        write_bvh(reduced.as_bvh_motion(), args.out)
        print(f"wrote {args.out}")
    if args.report:
        for path in write_reduction_report(curves, reduction, args.report, source, steps):
            print(f"wrote {path}")
    return 0


def _reconstruct(args: argparse.Namespace) -> int:
    from synthesis.hands.report import reconstruction_errors, write_reconstruction_report
    from synthesis.skeleton.bvh import write_bvh

    motion, source = _motion(args, 120.0)
    from synthesis.hands.handover import reconstruct_motion

    database = str(args.database or "")
    rebuilt = reconstruct_motion(
        motion.rig,
        motion.dofs_rad,
        motion.rate_hz,
        args.markers,
        args.method,
        database,
        args.lwr_variance,
    )
    if args.out:
        write_bvh(motion.rig.as_motion(rebuilt, motion.rate_hz), args.out)
        print(f"wrote {args.out}")
    if args.report:
        errors = reconstruction_errors(motion, args.method, source, database, args.lwr_variance)
        for row in errors.rows:
            published = (
                f"published {row['published_cm']} cm (seed 000 Table 3.1, p = 1000)"
                if row["published_cm"] is not None
                else "not published"
            )
            print(f"m = {row['markers']:>2}: {row['error_cm']:.2f} cm; {published}")
        for path in write_reconstruction_report(errors, args.report):
            print(f"wrote {path}")
    return 0


def _database(args: argparse.Namespace) -> int:
    from synthesis.hands.posedb import combined, engine_pose_database, recorded_pose_database

    parts = []
    if args.speeds:
        parts.append(
            engine_pose_database(
                args.side, tuple(args.speeds), tuple(args.words), args.simulated, args.root
            )
        )
    if args.recordings:
        parts.append(recorded_pose_database(args.recordings, args.side, args.root))
    if args.human_letters:
        from synthesis.hands.posedb import human_letter_poses, pose_database_of
        from synthesis.rigs.hand import HandModel

        poses = human_letter_poses(args.side, args.human_letters)
        source = f"human letters {args.human_letters.upper()} (spoken-to-signed)"
        parts.append(pose_database_of(HandModel(args.side), poses, source, args.root))
    if not parts:
        raise ValueError(
            "Nothing to put in the database: give recordings, --human-letters or --speeds."
        )
    database = combined(*parts) if len(parts) > 1 else parts[0]
    database.write(args.out)
    print(f"wrote {args.out}: {database.source}")
    return 0


def parser() -> argparse.ArgumentParser:
    """Return the argument parser of ``python -m synthesis.hands``."""
    root = argparse.ArgumentParser(
        prog="python -m synthesis.hands", description=__doc__.split("\n\n")[0]
    )
    commands = root.add_subparsers(dest="command", required=True)
    reduce = commands.add_parser("reduce", help="seed 002's DOF reduction of a hand motion")
    reduce.add_argument("motion", nargs="?", type=Path)
    reduce.add_argument("--spell", metavar="WORD", help="reduce the engine's spelling of WORD")
    reduce.add_argument(
        "--human-letters",
        metavar="LETTERS",
        default="",
        help="reduce spoken-to-signed's human recordings of these letters, one after another",
    )
    reduce.add_argument("--side", choices=("right", "left"), default="right")
    reduce.add_argument(
        "--range-deg",
        type=float,
        default=1.0,
        help="curves moving less than this become their mean (seed: 1 or 5)",
    )
    reduce.add_argument(
        "--rmsd",
        type=float,
        default=0.3,
        help="related curves closer than this are rebuilt (seed: 0.3 or 0.5)",
    )
    reduce.add_argument("--out", type=Path, help="the reduced motion (BVH)")
    reduce.add_argument("--report", type=Path, help="a directory for the tables and figure")
    reduce.set_defaults(run=_reduce)
    rebuild = commands.add_parser("reconstruct", help="seed 000's full hand from sparse markers")
    rebuild.add_argument("motion", nargs="?", type=Path)
    rebuild.add_argument("--spell", metavar="WORD", help="rebuild the engine's spelling of WORD")
    rebuild.add_argument("--side", choices=("right", "left"), default="right")
    rebuild.add_argument(
        "--markers",
        type=int,
        default=3,
        choices=range(1, 14),
        metavar="M",
        help="how many markers are kept (1–13; seed 000: 3 and 6)",
    )
    rebuild.add_argument("--method", choices=("lwr", "nearest"), default="lwr")
    rebuild.add_argument(
        "--lwr-variance",
        type=float,
        default=LWR_VARIANCE,
        help="share of the joint angles' variance LWR's principal components keep "
        "(1: all of them, seed 000 §3.2.4; then LWR equals direct regression)",
    )
    rebuild.add_argument("--out", type=Path, help="the rebuilt motion (BVH)")
    rebuild.add_argument(
        "--report", type=Path, help="a directory for the marker ranking and errors by marker count"
    )
    rebuild.add_argument(
        "--database",
        type=Path,
        help="a pose database (python -m synthesis.hands database); default: the engine's alphabet",
    )
    rebuild.set_defaults(run=_reconstruct)
    add_markers_command(commands)
    database = commands.add_parser("database", help="write a pose database to rebuild from")
    database.add_argument(
        "recordings",
        nargs="*",
        type=Path,
        help="hand recordings to add (engine hand BVH, captured .pose)",
    )
    database.add_argument("--words", nargs="*", default=[], help="words the engine spells too")
    database.add_argument(
        "--speeds",
        nargs="*",
        type=float,
        default=[1.0, 1.6],
        help="speed factors of the engine's spelling (1 = its own pace); none: leave the "
        "engine's letters out",
    )
    database.add_argument(
        "--simulated", type=int, default=0, help="simulated captures of each word to add"
    )
    database.add_argument(
        "--human-letters",
        metavar="LETTERS",
        default="",
        help="add these of spoken-to-signed's human letters (e.g. ABCDEFGHIJKLMNOPQRSTUVWXYZ)",
    )
    database.add_argument(
        "--root",
        choices=ROOTS,
        default="wrist",
        help="the markers' root link: wrist (digits only, the engine's) or forearm (seed "
        "000's, the wrist rebuilt too)",
    )
    database.add_argument("--side", choices=("right", "left"), default="right")
    database.add_argument("--out", type=Path, required=True)
    database.set_defaults(run=_database)
    return root


def main(argv: list[str] | None = None) -> int:
    """Run the command line; return its exit status (2 with a message on bad input)."""
    args = parser().parse_args(argv)
    try:
        return args.run(args)
    except (HandMotionError, ValueError) as error:
        print(f"error: {error}", file=sys.stderr)
        return 2
