"""Command line of the animation engine: ``python -m synthesis landmarks ABC``.

Rendering commands (render-pose, spell, render-bvh) arrive with the avatar and renderer.
"""

import argparse
import json
import sys

from synthesis.alphabet import AlphabetError, letter_pose
from synthesis.hand import HandModel
from synthesis.landmarks import landmarks


def _landmarks(args: argparse.Namespace) -> int:
    model = HandModel(args.side)
    letters = [character for character in args.letters if not character.isspace()]
    result = {}
    for character in letters:
        points = landmarks(model, letter_pose(character, args.side))
        result[character.upper()] = [[round(float(v), 6) for v in point] for point in points]
    print(json.dumps(result, indent=args.indent))
    return 0


def parser() -> argparse.ArgumentParser:
    """Build the command-line parser."""
    main = argparse.ArgumentParser(prog="python -m synthesis", description=__doc__)
    commands = main.add_subparsers(dest="command", required=True)
    marks = commands.add_parser(
        "landmarks", help="print the 21 MediaPipe hand landmarks of letters as JSON (metres)"
    )
    marks.add_argument("letters", help="letters, e.g. ABC")
    marks.add_argument("--side", choices=("right", "left"), default="right")
    marks.add_argument("--indent", type=int, default=None)
    marks.set_defaults(run=_landmarks)
    return main


def main(argv: list[str] | None = None) -> int:
    """Run the command line; bad input prints one error line and returns 2."""
    args = parser().parse_args(argv)
    try:
        return args.run(args)
    except AlphabetError as error:
        print(f"error: {error}", file=sys.stderr)
        return 2
