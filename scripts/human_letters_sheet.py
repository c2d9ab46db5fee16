"""Draw real signers' ASL letters, fitted onto our hand, next to the engine's own letters.

    .venv/bin/python scripts/human_letters_sheet.py docs/img/human-letters.png

The human letters are the ASL fingerspelling lexicon of the spoken-to-signed wheel (a
test dependency; its .pose files are read from the installed package, never copied
here). Each is its recording's middle frame, fitted with synthesis.capture.fit_hand and
shown with the forearm and wrist at rest (the fit transfers the handshape, not the
hand's orientation). Row pairs: the engine's letter above, the human one below.
"""

import argparse
import sys
from pathlib import Path

import numpy as np
from PIL import Image, ImageDraw, ImageFont

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from scripts.alphabet_sheet import FONT, _camera
from synthesis.avatar.hand_mesh import hand_avatar
from synthesis.capture import read_pose
from synthesis.capture.fidelity import view_of
from synthesis.capture.lexicon import human_letter_files
from synthesis.fingerspelling.alphabet import LETTERS, letter
from synthesis.render.renderer import Renderer

TILE = 220
COLUMNS = 13


def human_pose(model, path: Path) -> tuple[np.ndarray, float]:
    """Return the fitted DOFs of a recording's middle frame and its median residual (mm)."""
    view = view_of(model, *read_pose(path).hand(model.side))
    return view.dofs_rad, view.residual_mm


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out", type=Path)
    args = parser.parse_args()
    avatar = hand_avatar("right")
    files = human_letter_files()
    rows = 2 * -(-len(LETTERS) // COLUMNS)
    sheet = Image.new("RGB", (COLUMNS * TILE, rows * TILE), "white")
    font = ImageFont.truetype(FONT, 24) if Path(FONT).exists() else ImageFont.load_default()
    with Renderer(avatar, _camera(avatar, avatar.bind_dofs_rad), TILE, TILE) as renderer:
        for number, name in enumerate(LETTERS):
            shape = letter(name, "right")
            engine = shape.path_rad[-1] if shape.path_rad is not None else shape.dofs_rad
            human, residual = human_pose(avatar.rig, files[name])
            x, y = (number % COLUMNS) * TILE, 2 * (number // COLUMNS) * TILE
            for row, (pose, label) in enumerate(
                ((engine, f"{name} engine"), (human, f"{name} human {residual:.0f} mm"))
            ):
                renderer.set_camera(_camera(avatar, pose))
                tile = Image.fromarray(renderer.frame(np.asarray(pose)))
                ImageDraw.Draw(tile).text((8, 6), label, fill="white", font=font)
                sheet.paste(tile, (x, y + row * TILE))
    args.out.parent.mkdir(parents=True, exist_ok=True)
    sheet.save(args.out, optimize=True)
    print(f"wrote {args.out}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
