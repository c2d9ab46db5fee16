"""Render the spine study's sentences 2–4 with the spine on and off at the same instants.

    .venv/bin/python scripts/spine_comparison.py docs/img/spine_comparison.png

For each sentence, the three instants where the automated motion turns or bends the
torso most; top row spine on, bottom row spine off (issue 5's visual check: on shows
lateral bend and twist, off none). Also writes the torso-angle plots beside it.
"""

import argparse
import sys
from pathlib import Path

import numpy as np
from PIL import Image, ImageDraw, ImageFont

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from synthesis.avatar.body_mesh import body_avatar
from synthesis.render.renderer import Renderer
from synthesis.render.scene import upper_body_front
from synthesis.signing.sentence import SentenceOptions, synthesize
from synthesis.signing.sentence_plots import torso_angles, torso_angles_figure
from synthesis.signing.stories import SPINE_STORY

TILE = 300
FONT = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf"


def _instants(on, off, count: int = 3) -> list[int]:
    """Return frames where on and off differ most in torso angles, well apart."""
    a, b = torso_angles(on), torso_angles(off)
    difference = sum(np.abs(a[k] - b[k]) for k in a)
    chosen = []
    for frame in np.argsort(difference)[::-1]:
        if all(abs(frame - c) > on.rate_hz * 0.6 for c in chosen):
            chosen.append(int(frame))
        if len(chosen) == count:
            break
    return sorted(chosen)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out", type=Path)
    args = parser.parse_args()
    avatar = body_avatar()
    font = ImageFont.truetype(FONT, 15) if Path(FONT).exists() else ImageFont.load_default()
    sentences = SPINE_STORY[1:4]
    columns = 3 * len(sentences)
    sheet = Image.new("RGB", (columns * TILE, 2 * TILE), "white")
    with Renderer(avatar, upper_body_front(), TILE, TILE) as renderer:
        for s, text in enumerate(sentences):
            on = synthesize(text, SentenceOptions(spine=True))
            off = synthesize(text, SentenceOptions(spine=False))
            for k, frame in enumerate(_instants(on, off)):
                for row, version in enumerate((on, off)):
                    tile = Image.fromarray(renderer.frame(version.dofs_rad[frame]))
                    label = f"S{s + 2} {frame / on.rate_hz:.2f} s spine {('on', 'off')[row]}"
                    ImageDraw.Draw(tile).text((8, 6), label, fill="white", font=font)
                    sheet.paste(tile, ((3 * s + k) * TILE, row * TILE))
            figure = torso_angles_figure(on, off, title=text)
            plot = args.out.with_name(f"{args.out.stem}_torso_s{s + 2}.png")
            figure.savefig(plot, dpi=100)
            print(f"wrote {plot}")
    args.out.parent.mkdir(parents=True, exist_ok=True)
    sheet.save(args.out, optimize=True)
    print(f"wrote {args.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
