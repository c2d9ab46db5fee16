"""Render the simple and the human signer side by side, as one contact sheet.

    .venv/bin/python scripts/avatar_sheet.py docs/img/avatars.png

Columns: fingerspelled B, a wh-question's brows (the story's WHERE) and SAD, each in the
signing view at 640×480 (the 4:3 camera both avatars share); rows: the simple avatar,
kept for studies made with it, and the human one, the default (issue 36).
"""

import argparse
import sys
from pathlib import Path

import numpy as np
from PIL import Image, ImageDraw, ImageFont

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from synthesis.avatar.looks import Look
from synthesis.fingerspelling.alphabet import letter
from synthesis.render.renderer import Renderer
from synthesis.rigs.posture import hand_motion_on
from synthesis.signing.stories import SPINE_STORY
from synthesis.techniques import ClipRequest, avatar_and_camera, build_motion

FONT = "/usr/share/fonts/truetype/dejavu/DejaVuSans-Bold.ttf"
# Seconds into the story's second sentence: WHERE under its brows, then SAD.
MOMENTS_S = {"where (rhq brows)": 1.6, "SAD": 6.1}


def _poses(rig) -> dict[str, np.ndarray]:
    poses = {"letter B": hand_motion_on(rig, "right", letter("B", "right").dofs_rad[None])[0]}
    request = ClipRequest.from_parameters("sentence", SPINE_STORY[1], {"rate_hz": 30.0})
    motion = np.asarray(build_motion(request).motion)
    for name, seconds in MOMENTS_S.items():
        poses[name] = motion[min(int(seconds * 30), len(motion) - 1)]
    return poses


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out", type=Path)
    args = parser.parse_args()
    font = ImageFont.truetype(FONT, 22) if Path(FONT).exists() else ImageFont.load_default()
    rows = []
    for name in ("simple", "human"):
        avatar, camera = avatar_and_camera("upper-body", "right", Look(avatar=name))
        with Renderer(avatar, camera) as renderer:
            tiles = []
            for label, pose in _poses(avatar.rig).items():
                tile = Image.fromarray(renderer.frame(pose)[:, 80:560])
                ImageDraw.Draw(tile).text((10, 8), f"{name}: {label}", fill="white", font=font)
                tiles.append(np.asarray(tile))
        rows.append(np.concatenate(tiles, axis=1))
    args.out.parent.mkdir(parents=True, exist_ok=True)
    Image.fromarray(np.concatenate(rows, axis=0)).save(args.out, optimize=True)
    print(f"wrote {args.out}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
