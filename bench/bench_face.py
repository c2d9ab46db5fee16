"""Measure how MediaPipe reads the signer's face in the demo sentences (issue 36).

    .venv/bin/python bench/bench_face.py [--size 1280x720] [--avatar human|simple]

Every frame of the spine study's story and of the ASL-first demo's signed prompts
(spine on, 30 fps) is rendered in the signing view and given whole to MediaPipe
Holistic as a video (its pose model finds the signer, its Face Mesh model reads the
face); prints, per sentence, the frames with no face and when they are, and the total.
Face Mesh's own detector is short-range and finds almost no face of this size.
"""

import argparse
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from synthesis.avatar.looks import Look
from synthesis.render.renderer import Renderer
from synthesis.signing.stories import DEMO_SENTENCES
from synthesis.techniques import ClipRequest, build_motion, filming


def missed_frames(text: str, size: tuple[int, int], look: Look, holistic) -> tuple[int, list]:
    """Return how many frames *text* has and those in which MediaPipe finds no face."""
    parameters = {"rate_hz": 30.0, "width": size[0], "height": size[1], "spine": True}
    request = ClipRequest.from_parameters("sentence", text, parameters)
    motion = np.asarray(build_motion(request).motion)
    avatar, camera = filming(
        request.view,
        request.side,
        motion,
        request.rate_hz,
        request.width,
        request.height,
        look=look,
    )
    missed = []
    with Renderer(avatar, camera, width=size[0], height=size[1]) as renderer, holistic() as model:
        for number, dofs in enumerate(motion):
            if model.process(renderer.frame(dofs)).face_landmarks is None:
                missed.append(number)
    return len(motion), missed


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--size", default="1280x720")
    parser.add_argument("--avatar", default="human", choices=["human", "simple"])
    arguments = parser.parse_args()
    from mediapipe.python import solutions

    size = tuple(int(value) for value in arguments.size.split("x"))

    def holistic():
        return solutions.holistic.Holistic(static_image_mode=False, refine_face_landmarks=True)

    started = time.perf_counter()
    frames = found = 0
    for text in DEMO_SENTENCES:
        count, missed = missed_frames(text, size, Look(avatar=arguments.avatar), holistic)
        frames, found = frames + count, found + count - len(missed)
        when = ", ".join(f"{number / 30:.2f} s" for number in missed)
        print(
            f"{text[:48]:<48} {count:4d} frames, no face in {len(missed)}"
            + (f" (at {when})" if missed else "")
        )
    print(
        f"face found in {found} of {frames} frames ({found / frames:.1%}), {arguments.avatar} "
        f"avatar, {size[0]}×{size[1]} ({time.perf_counter() - started:.0f} s)"
    )
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
