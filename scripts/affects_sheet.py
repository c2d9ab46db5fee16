"""Render the face's affects (the library's happy, sad and surprise) as one contact sheet.

    .venv/bin/python scripts/affects_sheet.py docs/img/affects.png

The default human in the 16:9 signing view at 1280×720, cropped to the face and shown at
twice its size: neutral, then each affect at full intensity as the sign library defines
it (tests/synthesis/test_human_face.py reads them with MediaPipe).
"""

import argparse
import sys
from pathlib import Path

import numpy as np
from PIL import Image, ImageDraw, ImageFont

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from synthesis.avatar.looks import Look, avatar_for
from synthesis.render.renderer import Renderer
from synthesis.render.scene import project_px, signing_view
from synthesis.signing.signs import default_library

FONT = "/usr/share/fonts/truetype/dejavu/DejaVuSans-Bold.ttf"
AFFECTS = ("happy", "sad", "surprise")


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out", type=Path)
    args = parser.parse_args()
    font = ImageFont.truetype(FONT, 20) if Path(FONT).exists() else ImageFont.load_default()
    avatar = avatar_for("upper-body", "right", Look())
    camera = signing_view("right", 1280, 720)
    head = avatar.bind_pose.positions_m[0, avatar.rig.skeleton.index("head")]
    x, y = project_px(camera, head + np.array([0.0, 0.08, 0.0]), 1280, 720).astype(int)
    markers = default_library().nonmanuals
    tiles = []
    with Renderer(avatar, camera, 1280, 720) as renderer:
        for name in ("neutral", *AFFECTS):
            degrees = {} if name == "neutral" else dict(markers[name].face_deg)
            frame = renderer.frame(avatar.rig.from_degrees(degrees))[
                y - 75 : y + 75, x - 60 : x + 60
            ]
            tile = Image.fromarray(frame).resize((240, 300), Image.LANCZOS)
            ImageDraw.Draw(tile).text((8, 6), name, fill=(255, 255, 255), font=font)
            tiles.append(np.asarray(tile))
    Image.fromarray(np.concatenate(tiles, axis=1)).save(args.out, optimize=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
