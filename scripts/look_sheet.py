"""Render a story sentence's frames in the signing view at 1280×720, or stack such rows.

    .venv/bin/python scripts/look_sheet.py row new.png --label "new"
    .venv/bin/python scripts/look_sheet.py stack docs/img/look-old-new.png old.png new.png

A row is four moments of BUT SURPRISE MY BROTHER GET NEW (SURPRISE at the eyes, MY on
the chest, BROTHER at the forehead, GET), cropped to the signer. Run ``row`` in a
checkout of an earlier engine for the old look (issue 52: hard shadows on the chest and
over the mouth, anatomy through the top), then ``stack`` the rows into one sheet.
"""

import argparse
import sys
from pathlib import Path

import numpy as np
from PIL import Image, ImageDraw, ImageFont

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

FONT = "/usr/share/fonts/truetype/dejavu/DejaVuSans-Bold.ttf"
SENTENCE = "BUT SURPRISE MY BROTHER GET NEW"
FRAMES_AT_30_HZ = (20, 35, 50, 65)
CROP = (slice(40, 680), slice(330, 950))


def _font(size: int):
    return ImageFont.truetype(FONT, size) if Path(FONT).exists() else ImageFont.load_default()


def row(out: Path, label: str) -> None:
    """Render the sentence's moments in one labelled row."""
    from synthesis.render.renderer import Renderer
    from synthesis.techniques import ClipRequest, build_motion, filming

    request = ClipRequest("sentence", SENTENCE, {}, width=1280, height=720, rate_hz=30)
    motion = np.asarray(build_motion(request).motion)
    avatar, camera = filming("upper-body", "right", motion, 30, 1280, 720)
    with Renderer(avatar, camera, 1280, 720) as renderer:
        tiles = [renderer.frame(motion[k])[CROP] for k in FRAMES_AT_30_HZ]
    image = Image.fromarray(np.concatenate(tiles, axis=1))
    ImageDraw.Draw(image).text((12, 8), label, fill=(255, 255, 255), font=_font(28))
    image.save(out)


def stack(out: Path, rows: list[Path]) -> None:
    """Stack rows into one sheet, halved in size for the docs."""
    images = [np.asarray(Image.open(path).convert("RGB")) for path in rows]
    sheet = Image.fromarray(np.concatenate(images, axis=0))
    sheet.resize((sheet.width // 2, sheet.height // 2), Image.LANCZOS).save(out, optimize=True)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("mode", choices=("row", "stack"))
    parser.add_argument("out", type=Path)
    parser.add_argument("rows", type=Path, nargs="*")
    parser.add_argument("--label", default="")
    args = parser.parse_args()
    if args.mode == "row":
        row(args.out, args.label)
    else:
        stack(args.out, args.rows)
    return 0


if __name__ == "__main__":
    sys.exit(main())
