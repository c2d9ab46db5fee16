"""Render the face's expressions on the upper-body avatar as one labelled contact sheet.

    .venv/bin/python scripts/face_sheet.py docs/img/face.png [--avatar human|simple]

Each expression of synthesis.rigs.face.EXPRESSIONS twice: on the face close-up, and
beneath it at the signing view's own pixels (the head cut out of a 640×480 frame of the
sentence camera, not scaled), which is what a participant sees. Used to check the face
by eye: brows, lids and lashes, gaze and mouth shapes should read at both sizes.
"""

import argparse
import sys
from pathlib import Path

import numpy as np
from PIL import Image, ImageDraw, ImageFont

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from synthesis.avatar.looks import Look, avatar_for
from synthesis.render.renderer import Renderer
from synthesis.render.scene import face_close_up, project_px, upper_body_front
from synthesis.rigs.face import EXPRESSIONS

TILE = 300
COLUMNS = 6
SMALL = 110  # pixels of the signing view's frame around the head
FONT = "/usr/share/fonts/truetype/dejavu/DejaVuSans-Bold.ttf"


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out", type=Path)
    parser.add_argument("--avatar", choices=("human", "simple"), default="human")
    args = parser.parse_args()
    avatar = avatar_for("upper-body", "right", Look(avatar=args.avatar))
    rig = avatar.rig
    close = face_close_up()
    signing = upper_body_front()
    centre = project_px(signing, np.asarray(close.target_m), 640, 480)
    left, top = int(centre[0] - SMALL / 2), int(centre[1] - SMALL / 2)
    names = list(EXPRESSIONS)
    rows = -(-len(names) // COLUMNS)
    height = TILE + SMALL + 8
    sheet = Image.new("RGB", (COLUMNS * TILE, rows * height), "white")
    font = ImageFont.truetype(FONT, 20) if Path(FONT).exists() else ImageFont.load_default()
    with Renderer(avatar, close, TILE, TILE) as near, Renderer(avatar, signing) as far:
        for number, name in enumerate(names):
            pose = rig.from_degrees(EXPRESSIONS[name])
            x, y = (number % COLUMNS) * TILE, (number // COLUMNS) * height
            tile = Image.fromarray(near.frame(pose))
            ImageDraw.Draw(tile).text((10, 6), name, fill="white", font=font)
            sheet.paste(tile, (x, y))
            small = far.frame(pose)[top : top + SMALL, left : left + SMALL]
            sheet.paste(Image.fromarray(small), (x + (TILE - SMALL) // 2, y + TILE + 4))
    args.out.parent.mkdir(parents=True, exist_ok=True)
    sheet.save(args.out, optimize=True)
    print(f"wrote {args.out} ({len(names)} expressions)")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
