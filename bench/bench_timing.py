"""Time the Variable timing model: one 10-letter word's timing and poses, LOO, extraction.

Targets (issue 4): timing + poses for a 10-letter word in < 10 ms (no rendering); naïve
Bayes leave-one-out on 300 holds in < 2 s. Prints medians; asserts nothing.

    .venv/bin/python bench/bench_timing.py
"""

import statistics
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from synthesis.fingerspelling.spelling import spell
from synthesis.timing import (
    HoldClassifier,
    extract,
    letter_distance,
    published_model,
    simulate_recording,
)
from synthesis.timing.defaults import published_holds

WORD = "PSYCHIATRY"


def _median_ms(run, repeats: int) -> float:
    times = []
    for _ in range(repeats):
        started = time.perf_counter()
        run()
        times.append((time.perf_counter() - started) * 1000)
    return statistics.median(times)


def main() -> None:
    model = published_model()
    spell(WORD, timing=model.timing(WORD))  # solve the letters' poses once (cached)
    timing_ms = _median_ms(lambda: model.timing(WORD), 50)
    both_ms = _median_ms(lambda: spell(WORD, timing=model.timing(WORD)), 50)
    samples = published_holds(np.random.default_rng(0))[:300]
    classifier = HoldClassifier.fit(samples)
    loo_ms = _median_ms(lambda: classifier.leave_one_out(samples), 5)
    print(
        f"{WORD}: timing {timing_ms:.2f} ms; timing + poses at 60 fps {both_ms:.2f} ms "
        f"(target < 10 ms)"
    )
    print(f"naïve Bayes leave-one-out on {len(samples)} holds: {loo_ms:.0f} ms (target < 2 s)")
    motion, _ = simulate_recording(WORD, np.random.default_rng(0), model)
    extract_ms = _median_ms(lambda: extract(motion, WORD), 3)
    print(
        f"extraction from a simulated {motion.n_frames}-frame capture of {WORD}: "
        f"{extract_ms:.0f} ms (no target)"
    )
    pairs = [("E", "Z"), ("A", "T"), ("W", "P")]
    for space in ("joints", "dofs"):
        each_ms = _median_ms(
            lambda sp=space: [letter_distance(a, b, space=sp) for a, b in pairs], 200
        )
        print(f"letter distance over {space}: {1000 * each_ms / len(pairs):.1f} µs a pair")
    from synthesis.fingerspelling.alphabet import letter_pose
    from synthesis.timing.gplvm import embed

    poses = np.array([letter_pose(x) for x in "ABCDEFGHIJKLMNOPQRSTUVWXYZ"])
    gplvm_ms = _median_ms(lambda: embed(poses), 1)
    print(
        f"GPLVM of the 26 letters (GPy, 2 latent dimensions): {gplvm_ms:.0f} ms, once (disk cache)"
    )


if __name__ == "__main__":
    main()
