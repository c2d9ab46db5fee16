"""Time BVH parsing (and writing) of a long full-body clip.

Target (issue 3): parse ≥ 50 MB/s. Prints MB/s; asserts nothing.

    .venv/bin/python bench/bench_bvh.py
"""

import statistics
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))
sys.path.insert(0, str(Path(__file__).resolve().parent))

from bodies import random_motion

from synthesis import format_bvh, parse_bvh


def main() -> None:
    motion = random_motion(12000, rate_hz=120)  # 100 s at 120 fps
    started = time.perf_counter()
    text = format_bvh(motion)
    write_s = time.perf_counter() - started
    size_mb = len(text.encode()) / 1e6
    times = []
    for _ in range(5):
        started = time.perf_counter()
        parse_bvh(text, length_unit="cm")
        times.append(time.perf_counter() - started)
    median = statistics.median(times)
    print(
        f"file: {size_mb:.1f} MB, {motion.n_frames} frames × "
        f"{motion.skeleton.channel_count} channels"
    )
    print(f"parse: median {median * 1000:.0f} ms = {size_mb / median:.0f} MB/s (target ≥ 50 MB/s)")
    print(f"write: {write_s * 1000:.0f} ms = {size_mb / write_s:.0f} MB/s")


if __name__ == "__main__":
    main()
