"""Measure third-party BVH retargeted onto the engine's body and the GLB export (issue 37).

    .venv/bin/python bench/bench_retarget.py

For each CMU clip of Debian's assimp-testmodels (/usr/share/assimp/models/BVH): the
mean and largest angle between each mapped bone's direction on the engine's upper body
and in the source, per bone and over all, and the retargeting time; then the time and
size of a demo sentence's GLB (human signer, its face keyed) against rendering it.
"""

import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

import machine

from synthesis.interchange import request_glb
from synthesis.rigs.body import BodyModel
from synthesis.rigs.retarget import bone_direction_errors_deg, retarget
from synthesis.skeleton.bvh import BvhError, read_bvh
from synthesis.techniques import ClipRequest, build_motion, render_request

MODELS = Path("/usr/share/assimp/models/BVH")


def main() -> int:
    print(machine.describe())
    body = BodyModel("right")
    clips = sorted(MODELS.glob("*.bvh"))
    if not clips:
        print(f"no BVH under {MODELS}: install assimp-testmodels (scripts/system-packages.txt)")
        return 1
    for path in clips:
        try:
            motion = read_bvh(path)
        except BvhError as error:
            print(f"{path.name}: refused: {error}")
            continue
        started = time.perf_counter()
        pose = retarget(motion, body)
        seconds = time.perf_counter() - started
        errors = bone_direction_errors_deg(motion, pose, body)
        every = np.concatenate(list(errors.values()))
        print(
            f"{path.name}: {motion.n_frames} frames at {motion.rate_hz:.0f} Hz, retargeted in "
            f"{seconds * 1000:.0f} ms; bone direction error mean {every.mean():.2f}°, "
            f"largest {every.max():.1f}° over {len(errors)} bones"
        )
        for bone, angles in errors.items():
            print(f"  {bone:28s} mean {angles.mean():6.2f}°  max {angles.max():6.1f}°")
    request = ClipRequest.from_parameters(
        "sentence", "INFORM-YOU [top BLUE] [assert MY FAVORITE COLOR].", {"rate_hz": 30.0}
    )
    build = build_motion(request)
    started = time.perf_counter()
    data = request_glb(request, build)
    glb_s = time.perf_counter() - started
    started = time.perf_counter()
    render_request(request, "/tmp/bench-retarget.mp4", build=build)
    render_s = time.perf_counter() - started
    print(
        f"GLB of a {len(build.motion)}-frame sentence: {glb_s * 1000:.0f} ms, "
        f"{len(data) / 1e6:.1f} MB; rendering it: {render_s:.1f} s "
        f"(GLB at {glb_s / render_s:.3f} of the render's time)"
    )
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
