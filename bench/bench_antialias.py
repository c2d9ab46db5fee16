"""Measure anti-aliasing: frame time and how close edges come to a supersampled image.

Issue 16: anti-aliased edges at the same or better speed. For the hand close-up and the
signing view at 640×480 this prints, per method, one renderer's frame rate over a
fingerspelled word and the edge error against a 4 × 4 supersampled reference of the
same frames (mean absolute difference in levels of 255 over the reference's edge
pixels; lower is better): no anti-aliasing, the renderer's FXAA pass, and 2 × 2
supersampling (drawn at 1280×960, averaged down). Frame rates are medians over
interleaved rounds. Asserts nothing.

    .venv/bin/python bench/bench_antialias.py [--frames 120] [--rounds 3]
"""

import argparse
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

import machine
import numpy as np

from synthesis.fingerspelling.spelling import spell
from synthesis.render.antialias import downsample, edge_error
from synthesis.render.backend import select_platform
from synthesis.render.renderer import Renderer
from synthesis.render.scene import hand_close_up, upper_body_front
from synthesis.rigs.posture import fingerspelling_posture

WIDTH, HEIGHT = 640, 480
# Methods: (name, scale the frame is drawn at, FXAA pass).
METHODS = (("none", 1, False), ("FXAA", 1, True), ("2×2 supersampling", 2, False))


def _views(n_frames: int):
    from synthesis.avatar.body_mesh import body_avatar
    from synthesis.avatar.hand_mesh import hand_avatar

    hand_motion = spell("HEAVENLY" * 4, rate_hz=60)[:n_frames]
    body = body_avatar("right")
    return [
        ("hand close-up", hand_avatar("right"), hand_close_up(), hand_motion),
        (
            "signing view",
            body,
            upper_body_front(),
            fingerspelling_posture(body.rig, "right", hand_motion),
        ),
    ]


def _frame_ms(renderer: Renderer, motion, scale: int) -> float:
    started = time.perf_counter()
    for frame in renderer.frames(motion):
        if scale > 1:
            downsample(frame, scale)
    return 1000 * (time.perf_counter() - started) / len(motion)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--frames", type=int, default=120)
    parser.add_argument("--rounds", type=int, default=3)
    args = parser.parse_args()
    print(machine.describe())
    print(f"OpenGL platform: {select_platform()}; {WIDTH}×{HEIGHT}")
    for view, avatar, camera, motion in _views(args.frames):
        samples = motion[:: max(len(motion) // 6, 1)][:6]
        with Renderer(avatar, camera, 4 * WIDTH, 4 * HEIGHT, antialias=False) as renderer:
            references = [downsample(renderer.frame(pose), 4) for pose in samples]
        renderers = {
            name: Renderer(avatar, camera, scale * WIDTH, scale * HEIGHT, antialias=fxaa)
            for name, scale, fxaa in METHODS
        }
        times: dict[str, list[float]] = {name: [] for name in renderers}
        try:
            for _ in range(args.rounds):
                for name, scale, _fxaa in METHODS:
                    times[name].append(_frame_ms(renderers[name], motion, scale))
            for name, scale, _fxaa in METHODS:
                renderer = renderers[name]
                errors = [
                    edge_error(downsample(renderer.frame(pose), scale), reference)
                    for pose, reference in zip(samples, references, strict=True)
                ]
                error = np.mean([e for e, _ in errors])
                ms = float(np.median(times[name]))
                base = float(np.median(times["none"]))
                print(
                    f"{view:13s} {name:18s} {1000 / ms:5.1f} fps ({ms:5.1f} ms, "
                    f"{ms / base:4.2f}× none) | edge error {error:5.1f} levels over "
                    f"{np.mean([n for _, n in errors]):6.0f} edge pixels"
                )
        finally:
            for renderer in renderers.values():
                renderer.close()


if __name__ == "__main__":
    main()
