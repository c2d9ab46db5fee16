"""Render the story sentences with data-driven Hermite joins around their fastest moment.

    .venv/bin/python scripts/hermite_sheet.py docs/img/hermite-no-fling.png

Issue 53, item 1: the Hermite joins of seed 001 (Eq. 3.16) once ran backwards in time and
flung both arms out sideways in these three sentences. One row per sentence at 60 fps in
the signing view: the five frames around the frame where the arm's joints turn fastest
under ``transition=hermite`` (83 ms apart), labelled with that peak speed beside the
keyed motion's (the measure of tests/synthesis/test_transition_speed.py), and below it
the keyed motion at the same instants.
"""

import argparse
import sys
from pathlib import Path

import numpy as np
from PIL import Image, ImageDraw, ImageFont

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

FONT = "/usr/share/fonts/truetype/dejavu/DejaVuSans-Bold.ttf"
STORY = (
    "BUT SURPRISE MY BROTHER GET NEW",
    "INFORM-YOU BLUE MY FAVORITE COLOR",
    "LOOKING-BACK REMEMBER ME SMALL",
)
RATE_HZ, WIDTH, HEIGHT = 60.0, 640, 360
OFFSETS = (-10, -5, 0, 5, 10)
CROP = (slice(10, 350), slice(110, 530))


def _motion(text: str, transition: str) -> np.ndarray:
    from synthesis.techniques import ClipRequest, build_motion

    request = ClipRequest(
        "sentence", text, {"transition": transition}, width=WIDTH, height=HEIGHT, rate_hz=RATE_HZ
    )
    return np.asarray(build_motion(request).motion)


def _speeds(motion: np.ndarray) -> np.ndarray:
    """Return each frame step's fastest joint speed (°/s)."""
    return np.degrees(np.abs(np.diff(motion, axis=0))).max(axis=1) * RATE_HZ


def main() -> int:
    from synthesis.render.renderer import Renderer
    from synthesis.techniques import filming

    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out", type=Path)
    args = parser.parse_args()
    font = ImageFont.truetype(FONT, 15) if Path(FONT).exists() else ImageFont.load_default()
    rows = []
    for text in STORY:
        motion, keyed = _motion(text, "hermite"), _motion(text, "keyed")
        speeds = _speeds(motion)
        peak = int(np.argmax(speeds))
        avatar, camera = filming("upper-body", "right", motion, RATE_HZ, WIDTH, HEIGHT)
        frames = [int(np.clip(peak + k, 0, len(motion) - 1)) for k in OFFSETS]
        with Renderer(avatar, camera, WIDTH, HEIGHT) as renderer:
            tiles = [renderer.frame(motion[f])[CROP] for f in frames]
            under = [renderer.frame(keyed[min(f, len(keyed) - 1)])[CROP] for f in frames]
        row = Image.fromarray(np.concatenate(tiles, axis=1))
        below = Image.fromarray(np.concatenate(under, axis=1))
        ImageDraw.Draw(below).text((8, 6), "keyed, same instants", fill=(255, 255, 255), font=font)
        label = (
            f"{text}: hermite peak {speeds[peak]:.0f} °/s at {peak / RATE_HZ:.2f} s, "
            f"keyed {_speeds(keyed).max():.0f} °/s"
        )
        ImageDraw.Draw(row).text((8, 6), label, fill=(255, 255, 255), font=font)
        rows += [np.asarray(row), np.asarray(below)]
        print(label)
    sheet = Image.fromarray(np.concatenate(rows, axis=0))
    sheet.resize((sheet.width // 2, sheet.height // 2), Image.LANCZOS).save(args.out, optimize=True)
    print(f"wrote {args.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
