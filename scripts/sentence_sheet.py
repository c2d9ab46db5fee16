"""Render a demo sentence's frames as one contact sheet, as a study films them.

    .venv/bin/python scripts/sentence_sheet.py docs/img/sentence-frames.png

The sentence goes through the same path as a study's clip (ClipRequest, build_motion,
film) at a new study's size, 1280×720, with the default human signer and its face on;
eight frames evenly spaced between the first and the last hold are shown at 480×270,
each labelled with its time.
"""

import argparse
import sys
from pathlib import Path

import numpy as np
from PIL import Image, ImageDraw, ImageFont

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from synthesis.render.renderer import Renderer
from synthesis.techniques import ClipRequest, build_motion
from synthesis.techniques.request import film

FONT = "/usr/share/fonts/truetype/dejavu/DejaVuSans-Bold.ttf"
SENTENCE = "FINALLY HAVE C-A-R AGAIN — HAPPY!"
TILES, COLUMNS, TILE_PX = 8, 4, (480, 270)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out", type=Path)
    parser.add_argument("--sentence", default=SENTENCE)
    args = parser.parse_args()
    font = ImageFont.truetype(FONT, 18) if Path(FONT).exists() else ImageFont.load_default()
    request = ClipRequest.from_parameters(
        "sentence", args.sentence, {"width": 1280, "height": 720, "face": "on"}
    )
    build = build_motion(request)
    avatar, camera = film(request, build)
    motion = np.asarray(build.made_motion)  # a sentence's DOF vectors
    total = len(motion)
    # The first and last tenth are the signer's rest: the sheet shows the signing.
    numbers = np.linspace(0.1 * total, 0.9 * total, TILES).astype(int)
    tiles = []
    with Renderer(avatar, camera, request.width, request.height) as renderer:
        for number in numbers:
            frame = renderer.frame(motion[number])
            tile = Image.fromarray(frame).resize(TILE_PX, Image.LANCZOS)
            label = f"{number / request.rate_hz:.2f} s"
            ImageDraw.Draw(tile).text((8, 6), label, fill=(255, 255, 255), font=font)
            tiles.append(np.asarray(tile))
    rows = [np.concatenate(tiles[k : k + COLUMNS], axis=1) for k in range(0, TILES, COLUMNS)]
    Image.fromarray(np.concatenate(rows, axis=0)).save(args.out, optimize=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
