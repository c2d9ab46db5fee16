"""Split a stimulus frame's time: skinning, the shadow pass, the scene's draw, FXAA.

Issue 52 asks where an HD frame's time goes. For a study's two views at a study's size
(the hand close-up spelling a demo word; the signing view signing a demo sentence with
its face), one renderer on one llvmpipe thread (as each of the stimulus pool's
processes renders; ``LP_NUM_THREADS=1``) draws the same frames four ways, interleaved
over rounds (medians): as studies render them, without FXAA, without the key light's
shadow, and without either; the skinning (blendshapes and linear blend skinning of
those frames) is timed alone. The split is the differences: FXAA = full − no FXAA,
shadow = full − no shadow, the rest of the draw (scene pass, read-back) = neither −
skinning. Asserts nothing.

    .venv/bin/python bench/bench_frame_split.py [--size 1280x720] [--frames 120] [--rounds 3]
"""

import argparse
import os
import statistics
import sys
import time
from dataclasses import replace
from pathlib import Path

os.environ["LP_NUM_THREADS"] = "1"  # before Mesa is loaded
sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

import machine
import numpy as np

from synthesis.render.backend import select_platform
from synthesis.render.renderer import BATCH_FRAMES, Renderer
from synthesis.render.scene import CameraPath, portrait_lighting
from synthesis.skeleton.kinematics import Pose
from synthesis.techniques import ClipRequest, build_motion
from synthesis.techniques.request import film

WORD = "GUITAR"
SENTENCE = "FINALLY HAVE C-A-R AGAIN — HAPPY!"


def _shadowless(camera) -> tuple:
    """Return the portrait lights of *camera* with no light casting a shadow."""
    target = np.asarray(camera.target_m)
    distance = float(np.linalg.norm(np.asarray(camera.eye_m) - target))
    return tuple(
        replace(light, casts_shadow=False) for light in portrait_lighting(target, distance)
    )


def _frames(motion, start: int, stop: int):
    """Return frames start … stop − 1 of DOF vectors or a Pose."""
    if isinstance(motion, Pose):
        return Pose(motion.quaternions[start:stop], motion.positions_m[start:stop])
    return np.asarray(motion)[start:stop]


def _ms_per_frame(avatar, camera, motion, count, width, height, **options) -> float:
    """Return one renderer's mean time per frame over *motion*'s first *count* frames."""
    with Renderer(avatar, camera, width, height, **options) as renderer:
        for _ in renderer.frames(motion):
            break  # shaders compiled, buffers made
        started = time.perf_counter()
        for number, _ in enumerate(renderer.frames(motion)):
            if number + 1 == count:
                break
        return 1000 * (time.perf_counter() - started) / count


def _skinning_ms(avatar, motion, count: int) -> float:
    """Return the skinning's time per frame, in the renderer's batches of frames."""
    started = time.perf_counter()
    for start in range(0, count, BATCH_FRAMES):
        batch = _frames(motion, start, min(start + BATCH_FRAMES, count))
        if isinstance(batch, Pose):
            avatar.deform_pose(batch)
        else:
            avatar.deform(batch)
    return 1000 * (time.perf_counter() - started) / count


def _split(name, request: ClipRequest, count: int, rounds: int) -> None:
    build = build_motion(request)
    avatar, camera = film(request, build)
    motion = build.made_motion
    camera_at = camera.at(0) if isinstance(camera, CameraPath) else camera
    ways = {
        "full": {},
        "no FXAA": {"antialias": False},
        "no shadow": {"lights": _shadowless(camera_at)},
        "neither": {"antialias": False, "lights": _shadowless(camera_at)},
    }
    size = (request.width, request.height)
    times: dict[str, list[float]] = {way: [] for way in ways}
    skinning = []
    for _ in range(rounds):
        for way, options in ways.items():
            times[way].append(_ms_per_frame(avatar, camera, motion, count, *size, **options))
        skinning.append(_skinning_ms(avatar, motion, count))
    ms = {way: statistics.median(values) for way, values in times.items()}
    skin = statistics.median(skinning)
    print(
        f"{name:<13} {ms['full']:5.1f} ms a frame: skinning {skin:4.1f}, "
        f"shadow {ms['full'] - ms['no shadow']:4.1f}, FXAA {ms['full'] - ms['no FXAA']:4.1f}, "
        f"scene draw and read-back {ms['neither'] - skin:4.1f} "
        f"({avatar.triangle_count} triangles, {request.width}×{request.height})"
    )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--size", default="1280x720")
    parser.add_argument("--frames", type=int, default=120)
    parser.add_argument("--rounds", type=int, default=3)
    args = parser.parse_args()
    width, height = (int(value) for value in args.size.split("x"))
    print(machine.describe())
    print(f"OpenGL platform: {select_platform()}; one llvmpipe thread")
    size = {"width": width, "height": height, "rate_hz": 60.0}
    word = ClipRequest.from_parameters("word", WORD, {**size, "view": "hand"})
    sentence = ClipRequest.from_parameters("sentence", SENTENCE, {**size, "face": "on"})
    _split("hand close-up", word, args.frames, args.rounds)
    _split("signing view", sentence, args.frames, args.rounds)


if __name__ == "__main__":
    main()
