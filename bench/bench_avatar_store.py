"""Measure the on-disk avatar store (issue 16): building each avatar against loading it.

    .venv/bin/python bench/bench_avatar_store.py

Builds the hand and upper-body avatars with the store off, then stores them in a
temporary directory and loads them back (each load in a fresh process, as a render
worker starts), and prints seconds and the ratio. Then a short clip (ABLE, 320×240)
rendered by a fresh process with the store off and with the store warm: the time a
newcomer's render workers save per process.
"""

import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))
sys.path.insert(0, str(Path(__file__).resolve().parent))

import machine

from synthesis.avatar.store import CACHE_ENV

ROOT = Path(__file__).resolve().parent.parent
# The call alone, its imports done first (the engine's digest, read once a process, counts).
LOAD = (
    "import time; from synthesis.avatar import {0}; t = time.perf_counter(); {0}(); "
    "print(time.perf_counter() - t)"
)
CLIP = ["-m", "synthesis", "spell", "ABLE", "--size", "320x240"]


def _run(arguments: list[str], store: str) -> tuple[float, str]:
    """Run the interpreter with *arguments* and the store at *store*; return (s, output)."""
    started = time.perf_counter()
    done = subprocess.run(
        [sys.executable, *arguments],
        cwd=ROOT,
        capture_output=True,
        text=True,
        env={**os.environ, CACHE_ENV: store},
        check=True,
    )
    return time.perf_counter() - started, done.stdout


def main() -> int:
    print(machine.describe())
    with tempfile.TemporaryDirectory() as directory:
        for avatar in ("hand_avatar", "body_avatar"):
            _, built = _run(["-c", LOAD.format(avatar)], "off")
            _run(["-c", LOAD.format(avatar)], directory)  # stores it
            _, loaded = _run(["-c", LOAD.format(avatar)], directory)
            built_s, loaded_s = float(built), float(loaded)
            print(
                f"{avatar}: build {built_s:.2f} s, load {1000 * loaded_s:.0f} ms "
                f"({built_s / loaded_s:.0f}× faster)"
            )
        clip = str(Path(directory) / "able.mp4")
        cold, _ = _run([*CLIP, "--out", clip], "off")
        warm, _ = _run([*CLIP, "--out", clip], directory)
        print(
            f"ABLE, 320×240, one fresh process: {cold:.1f} s with the store off, "
            f"{warm:.1f} s with it warm (saves {cold - warm:.1f} s)"
        )
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
