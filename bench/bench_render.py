"""Measure rendering speed at 640×480: the hand close-up and the upper body.

Target (issue 3, and issue 16 for the upper body with its face): ≥ 30 fps on the 2-core
reference machine. Prints, per view: avatar
build time, frames per second of one renderer (skinning + drawing, Mesa's threads on
all cores), of the parallel path render_clip uses (one process per core), and of a whole
clip written to MP4 with those workers (rendering + H.264 encoding). Parallel figures
include starting the worker processes. Asserts nothing.

    .venv/bin/python bench/bench_render.py [--frames 600]
"""

import argparse
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

import machine

from synthesis.fingerspelling.spelling import spell
from synthesis.render.backend import select_platform
from synthesis.render.clip import render_clip
from synthesis.render.parallel import default_workers, render_frames
from synthesis.render.renderer import Renderer
from synthesis.render.scene import hand_close_up, upper_body_front
from synthesis.rigs.posture import fingerspelling_posture


def _views(n_frames: int):
    from synthesis.avatar.body_mesh import body_avatar
    from synthesis.avatar.hand_mesh import hand_avatar

    word = "HEAVENLY" * 4
    hand_motion = spell(word, rate_hz=60)[:n_frames]
    started = time.perf_counter()
    hand = hand_avatar("right")
    hand_build = time.perf_counter() - started
    started = time.perf_counter()
    body = body_avatar("right")
    body_build = time.perf_counter() - started
    body_motion = fingerspelling_posture(body.rig, "right", hand_motion)
    return [
        ("hand close-up", hand, hand_close_up(), hand_motion, hand_build),
        ("upper body", body, upper_body_front(), body_motion, body_build),
    ]


def _fps(frames, count: int) -> float:
    started = time.perf_counter()
    for _ in frames:
        pass
    return count / (time.perf_counter() - started)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    # 600 frames: a 10 s clip at 60 fps, a typical sentence or a long fingerspelled word.
    parser.add_argument("--frames", type=int, default=600)
    args = parser.parse_args()
    print(machine.describe())
    print(f"OpenGL platform: {select_platform()}; render workers: {default_workers()}")
    for name, avatar, camera, motion, build_s in _views(args.frames):
        n = len(motion)
        with Renderer(avatar, camera, 640, 480) as renderer:
            renderer.frame(motion[0])  # compile shaders first
            single = _fps(renderer.frames(motion), n)
        workers = default_workers()
        parallel = _fps(render_frames(avatar, camera, motion, 640, 480, workers), n)
        with tempfile.TemporaryDirectory() as folder:
            started = time.perf_counter()
            render_clip(avatar, motion, camera, Path(folder) / "clip.mp4", workers=workers)
            clip = n / (time.perf_counter() - started)
        print(
            f"{name:14s} {avatar.triangle_count:6d} triangles, built in {build_s:4.1f} s | "
            f"one renderer {single:5.1f} fps | {workers} workers {parallel:5.1f} fps | "
            f"MP4 clip {clip:5.1f} fps  ({n} frames, target ≥ 30 fps)"
        )


if __name__ == "__main__":
    main()
