"""Render an alphabet's letters as one labelled contact sheet, in the close-up or the
signing view.

    .venv/bin/python scripts/alphabet_sheet.py docs/img/alphabet.png [LETTERS] [--side left]
        [--avatar human|simple] [--view hand|upper-body] [--alphabet asl|libras]

Letters that move (J, Z) are shown at the end of their motion paths. Used to check the
alphabet data by eye: every letter should be recognisable to someone who knows the
alphabet. In the
signing view each tile is the hand's part of a 1280×720 frame of the signing camera, not
turned toward the hand: the palm as a participant sees it.
"""

import argparse
import sys
from pathlib import Path

import numpy as np
from PIL import Image, ImageDraw, ImageFont

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from synthesis.avatar.looks import Look, avatar_for
from synthesis.fingerspelling.alphabet import letter
from synthesis.fingerspelling.alphabets import alphabet_codes, manual_alphabet
from synthesis.render.renderer import Renderer
from synthesis.render.scene import CameraPreset, project_px, signing_view
from synthesis.rigs.posture import hand_motion_on

TILE = 320
COLUMNS = 7
FONT = "/usr/share/fonts/truetype/dejavu/DejaVuSans-Bold.ttf"


def _camera(avatar, pose) -> CameraPreset:
    """Frame the hand itself (wrist and digits), seen from the front like the video camera."""
    positions = avatar.rig.pose(np.asarray(pose)).positions_m[0]
    centre = positions[avatar.rig.skeleton.index("wrist") :].mean(axis=0)
    eye = centre + np.array([0.0, 0.02, 0.5])
    return CameraPreset("letter", tuple(eye), tuple(centre), 27.0)


def _letter_pose(name: str, side: str, alphabet: str) -> np.ndarray:
    shape = letter(name, side, alphabet)
    return np.asarray(shape.path_rad[-1] if shape.path_rad is not None else shape.dofs_rad)


def _close_up_tiles(letters, side: str, look: Look, alphabet: str):
    avatar = avatar_for("hand", side, look)
    with Renderer(avatar, _camera(avatar, avatar.bind_dofs_rad), TILE, TILE) as renderer:
        for name in letters:
            pose = _letter_pose(name, side, alphabet)
            renderer.set_camera(_camera(avatar, pose))
            yield renderer.frame(pose)


def _signing_view_tiles(letters, side: str, look: Look, alphabet: str):
    avatar = avatar_for("upper-body", side, look)
    camera = signing_view(side, 1280, 720)
    wrist = avatar.rig.skeleton.index(f"{side}_wrist")
    with Renderer(avatar, camera, 1280, 720) as renderer:
        for name in letters:
            dofs = hand_motion_on(avatar.rig, side, _letter_pose(name, side, alphabet)[None])[0]
            x, y = project_px(camera, avatar.rig.pose(dofs).positions_m[0, wrist], 1280, 720)
            # The hand rises above the wrist: the tile's centre is 40 px over it.
            left, top = int(x) - TILE // 2, int(y) - 40 - TILE // 2
            yield renderer.frame(dofs)[max(top, 0) : top + TILE, max(left, 0) : left + TILE]


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out", type=Path)
    parser.add_argument("letters", nargs="?", default="")
    parser.add_argument("--side", choices=("right", "left"), default="right")
    parser.add_argument("--avatar", choices=("human", "simple"), default="human")
    parser.add_argument("--view", choices=("hand", "upper-body"), default="hand")
    parser.add_argument("--alphabet", choices=alphabet_codes(), default="asl")
    args = parser.parse_args()
    manual = manual_alphabet(args.alphabet)
    letters = [manual.check(c) for c in args.letters] or list(manual.letters)
    rows = -(-len(letters) // COLUMNS)
    sheet = Image.new("RGB", (COLUMNS * TILE, rows * TILE), "white")
    font = ImageFont.truetype(FONT, 34) if Path(FONT).exists() else ImageFont.load_default()
    tiles = _close_up_tiles if args.view == "hand" else _signing_view_tiles
    for number, (name, pixels) in enumerate(
        zip(
            letters, tiles(letters, args.side, Look(avatar=args.avatar), args.alphabet), strict=True
        )
    ):
        tile = Image.fromarray(np.ascontiguousarray(pixels))
        ImageDraw.Draw(tile).text((12, 8), name, fill="white", font=font)
        sheet.paste(tile, ((number % COLUMNS) * TILE, (number // COLUMNS) * TILE))
    args.out.parent.mkdir(parents=True, exist_ok=True)
    sheet.save(args.out, optimize=True)
    print(f"wrote {args.out} ({len(letters)} letters)")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
