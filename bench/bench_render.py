"""Measure rendering speed (640×480, or --size): the hand close-up and the upper body.

Targets: ≥ 30 fps on the 2-core reference machine (issue 3; issue 16 for the upper body
with its face); issue 36, the human signer: one renderer ≥ 30 fps with the face moving,
the MP4 path ≥ 25 fps, the avatar built from MakeHuman's files once and loaded from the
disk cache in under 2 s. Prints, per avatar and view: the avatar's build time from
nothing (disk cache off) and its load from the disk cache, frames per second of one
renderer (skinning + blendshapes + drawing, Mesa's threads on all cores), of the
parallel path render_clip uses (one process per core), and of a whole clip written to
MP4 with those workers (rendering + H.264 encoding). The upper body signs a story
sentence with its non-manual signals (the face's channels move); the close-up spells.
Parallel figures include starting the worker processes. Asserts nothing.

    .venv/bin/python bench/bench_render.py [--frames 600] [--avatar human|simple|both]
        [--size 1280x720]

At --size the upper body is filmed by the signing view's camera for that frame (the 16:9
one at 1280×720, issue 52's study size).
"""

import argparse
import os
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

import machine
import numpy as np

from synthesis.fingerspelling.spelling import spell
from synthesis.render.backend import select_platform
from synthesis.render.clip import render_clip
from synthesis.render.parallel import default_workers, render_frames
from synthesis.render.renderer import Renderer
from synthesis.render.scene import hand_close_up, signing_view

# A story sentence with non-manual signals: the face's channels move (issue 36's target).
SENTENCE = "I LOST [rhq WHERE]. I SEARCH, SEARCH, [neg CAN'T FIND]."


def _timed(build):
    """Return what *build* returns, its time from nothing and its load from the disk cache."""
    from synthesis.diskcache import CACHE_ENV

    saved = os.environ.get(CACHE_ENV)
    os.environ[CACHE_ENV] = "off"
    started = time.perf_counter()
    build()
    cold = time.perf_counter() - started
    if saved is None:
        del os.environ[CACHE_ENV]
    else:
        os.environ[CACHE_ENV] = saved
    build()  # stored, if it was not
    started = time.perf_counter()
    avatar = build()
    return avatar, cold, time.perf_counter() - started


def _views(n_frames: int, look: str, width: int, height: int):
    from synthesis.techniques import ClipRequest, build_motion

    word = "HEAVENLY" * 4
    hand_motion = spell(word, rate_hz=60)[:n_frames]
    hand = _timed(lambda: _uncached("hand", look))
    body = _timed(lambda: _uncached("upper-body", look))
    sentence = ClipRequest.from_parameters("sentence", SENTENCE, {"rate_hz": 60.0})
    body_motion = np.asarray(build_motion(sentence).motion)
    body_motion = np.concatenate([body_motion] * (n_frames // len(body_motion) + 1))[:n_frames]
    return [
        (f"{look} close-up", *hand, hand_close_up(), hand_motion),
        (f"{look} upper body", *body, signing_view("right", width, height), body_motion),
    ]


def _uncached(view: str, look: str):
    """Return the avatar of *view* built or loaded anew (not from this process's memory)."""
    from synthesis.avatar.body_mesh import body_avatar
    from synthesis.avatar.hand_mesh import hand_avatar
    from synthesis.avatar.human.build import human_avatar
    from synthesis.avatar.human.hand import human_hand_avatar

    make = {
        ("hand", "simple"): hand_avatar,
        ("upper-body", "simple"): body_avatar,
        ("hand", "human"): human_hand_avatar,
        ("upper-body", "human"): human_avatar,
    }
    return make[view, look].__wrapped__("right")


def _fps(frames, count: int) -> float:
    started = time.perf_counter()
    for _ in frames:
        pass
    return count / (time.perf_counter() - started)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    # 600 frames: a 10 s clip at 60 fps, a typical sentence or a long fingerspelled word.
    parser.add_argument("--frames", type=int, default=600)
    parser.add_argument("--avatar", choices=("human", "simple", "both"), default="both")
    parser.add_argument("--size", default="640x480")
    args = parser.parse_args()
    width, height = (int(value) for value in args.size.split("x"))
    print(machine.describe())
    print(f"OpenGL platform: {select_platform()}; render workers: {default_workers()}")
    looks = ("human", "simple") if args.avatar == "both" else (args.avatar,)
    views = [view for look in looks for view in _views(args.frames, look, width, height)]
    for name, avatar, build_s, load_s, camera, motion in views:
        n = len(motion)
        with Renderer(avatar, camera, width, height) as renderer:
            renderer.frame(motion[0])  # compile shaders first
            single = _fps(renderer.frames(motion), n)
        workers = default_workers()
        parallel = _fps(render_frames(avatar, camera, motion, width, height, workers), n)
        with tempfile.TemporaryDirectory() as folder:
            started = time.perf_counter()
            out = Path(folder) / "clip.mp4"
            render_clip(avatar, motion, camera, out, width=width, height=height, workers=workers)
            clip = n / (time.perf_counter() - started)
        print(
            f"{name:19s} {avatar.triangle_count:6d} triangles, built in {build_s:4.1f} s, "
            f"loaded in {load_s:4.2f} s | "
            f"one renderer {single:5.1f} fps | {workers} workers {parallel:5.1f} fps | "
            f"MP4 clip {clip:5.1f} fps  ({n} frames at {width}×{height}, target ≥ 30 fps)"
        )


if __name__ == "__main__":
    main()
