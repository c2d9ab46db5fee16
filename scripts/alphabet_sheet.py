"""Render the 26 letters on the default hand avatar as one labelled contact sheet.

    .venv/bin/python scripts/alphabet_sheet.py docs/img/alphabet.png [LETTERS] [--side left]

J and Z are shown at the end of their motion paths. Used to check the alphabet data by
eye: every letter should be recognisable to someone who knows the ASL alphabet.
"""

import argparse
import sys
from pathlib import Path

import numpy as np
from PIL import Image, ImageDraw, ImageFont

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from synthesis.avatar.hand_mesh import hand_avatar
from synthesis.fingerspelling.alphabet import LETTERS, letter
from synthesis.render.renderer import Renderer
from synthesis.render.scene import CameraPreset

TILE = 320
COLUMNS = 7
FONT = "/usr/share/fonts/truetype/dejavu/DejaVuSans-Bold.ttf"


def _camera(avatar, pose) -> CameraPreset:
    """Frame the hand itself (wrist and digits), seen from the front like the video camera."""
    positions = avatar.rig.pose(np.asarray(pose)).positions_m[0]
    centre = positions[avatar.rig.skeleton.index("wrist") :].mean(axis=0)
    eye = centre + np.array([0.0, 0.02, 0.5])
    return CameraPreset("letter", tuple(eye), tuple(centre), 27.0)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out", type=Path)
    parser.add_argument("letters", nargs="?", default="".join(LETTERS))
    parser.add_argument("--side", choices=("right", "left"), default="right")
    args = parser.parse_args()
    avatar = hand_avatar(args.side)
    letters = [c.upper() for c in args.letters]
    rows = -(-len(letters) // COLUMNS)
    sheet = Image.new("RGB", (COLUMNS * TILE, rows * TILE), "white")
    font = ImageFont.truetype(FONT, 34) if Path(FONT).exists() else ImageFont.load_default()
    with Renderer(avatar, _camera(avatar, avatar.bind_dofs_rad), TILE, TILE) as renderer:
        for number, name in enumerate(letters):
            shape = letter(name, args.side)
            pose = shape.path_rad[-1] if shape.path_rad is not None else shape.dofs_rad
            renderer.set_camera(_camera(avatar, pose))
            tile = Image.fromarray(renderer.frame(np.asarray(pose)))
            ImageDraw.Draw(tile).text((12, 8), name, fill="white", font=font)
            sheet.paste(tile, ((number % COLUMNS) * TILE, (number // COLUMNS) * TILE))
    args.out.parent.mkdir(parents=True, exist_ok=True)
    sheet.save(args.out, optimize=True)
    print(f"wrote {args.out} ({len(letters)} letters)")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
