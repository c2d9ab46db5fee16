"""Time sentence synthesis on the full upper body at 60 fps, without rendering.

Target (issue 5): a 5 s sentence in < 50 ms. Prints the median of repeated runs for
each story sentence with the spine on and off, and the cost per second of motion.
Asserts nothing.

    .venv/bin/python bench/bench_sentence.py
"""

import statistics
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from synthesis.signing.sentence import SentenceOptions, synthesize
from synthesis.signing.stories import SPINE_STORY


def main() -> None:
    synthesize(SPINE_STORY[0])  # build the alphabet's letters and the library once
    for number, text in enumerate(SPINE_STORY, start=1):
        for spine in (True, False):
            options = SentenceOptions(spine=spine)
            times = []
            for _ in range(7):
                started = time.perf_counter()
                sentence = synthesize(text, options)
                times.append((time.perf_counter() - started) * 1000)
            median = statistics.median(times)
            per_5s = median / sentence.duration_s * 5
            print(
                f"sentence {number} ({sentence.duration_s:.1f} s, {len(sentence.dofs_rad)} "
                f"frames, spine {'on' if spine else 'off'}): {median:.1f} ms; "
                f"{per_5s:.1f} ms per 5 s (target < 50 ms)"
            )


if __name__ == "__main__":
    main()
