"""Describe how fast and how busy this machine is, so figures from different runs compare.

The same benchmark has given figures 1.5× apart on this machine in different sessions;
printing a fixed workload's time and the load average next to them tells a slower
machine from slower code.
"""

import os
import statistics
import time

import numpy as np


def baseline_ms(repeats: int = 3) -> float:
    """Return the best time of a fixed single-threaded Python and numpy workload, in ms."""
    rng = np.random.default_rng(0)
    data = rng.standard_normal((200, 3))
    best = float("inf")
    for _ in range(repeats):
        started = time.perf_counter()
        total = 0
        for i in range(1_000_000):
            total += i & 7
        for _ in range(200):
            np.linalg.norm(data[:, None, :] - data[None, :, :], axis=-1).sum()
        best = min(best, time.perf_counter() - started)
    return 1000 * best


def describe() -> str:
    """Return one line: cores, load average and the baseline workload's time."""
    load = ", ".join(f"{value:.2f}" for value in os.getloadavg())
    return (
        f"machine: {os.cpu_count()} cores, load average {load}, "
        f"baseline workload {baseline_ms():.0f} ms (fixed Python + numpy; lower is faster)"
    )


def timed_ms(function, repeat: int = 5) -> tuple[float, object]:
    """Return the median time of *repeat* calls of *function* in ms, and its last result."""
    times, result = [], None
    for _ in range(repeat):
        started = time.perf_counter()
        result = function()
        times.append((time.perf_counter() - started) * 1000)
    return statistics.median(times), result
