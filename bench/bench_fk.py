"""Time forward kinematics of 1,000 frames of a full body with hands.

Target (issue 3): < 20 ms. Prints the median of repeated runs; asserts nothing.

    .venv/bin/python bench/bench_fk.py
"""

import statistics
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))
sys.path.insert(0, str(Path(__file__).resolve().parent))

from bodies import random_motion

from synthesis import forward_kinematics


def main() -> None:
    motion = random_motion(1000)
    forward_kinematics(motion)  # warm up
    times = []
    for _ in range(20):
        started = time.perf_counter()
        forward_kinematics(motion)
        times.append((time.perf_counter() - started) * 1000)
    median = statistics.median(times)
    joints = len(motion.skeleton)
    print(
        f"FK of {motion.n_frames} frames × {joints} joints: median {median:.1f} ms "
        f"(min {min(times):.1f} ms), {motion.n_frames / median * 1000:,.0f} frames/s "
        f"(target < 20 ms)"
    )


if __name__ == "__main__":
    main()
