"""Time the stimulus check over every demo study's clips, and count what it finds.

Issue 52: the check runs on the motion alone (nothing is rendered), before anyone sees
a clip. Runs in a fresh temporary data directory (SQLite): loads the demo studies,
then ``manage.py check_stimuli`` once cold (every clip's motion and keyed reference
built and checked) and once warm (the checks read back by content hash). Prints the
figures and the warnings by kind; asserts nothing.

    .venv/bin/python bench/bench_stimulus_checks.py
"""

import collections
import os
import re
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import machine

ROOT = Path(__file__).resolve().parent.parent
KIND = {
    "turns at": "speed",
    "leaves the frame": "frame",
    "px at its smallest": "size",
    "into the body": "contact",
    "hides over half": "face",
}


def _manage(var_dir: Path, *arguments: str) -> tuple[float, str]:
    unset = ("DATABASE_URL", "CELERY_BROKER_URL", "REDIS_URL")
    environment = {k: v for k, v in os.environ.items() if k not in unset}
    environment["SIGNSTUDY_VAR_DIR"] = str(var_dir)
    started = time.perf_counter()
    command = [sys.executable, str(ROOT / "manage.py"), *arguments]
    done = subprocess.run(command, check=True, env=environment, cwd=ROOT, capture_output=True)
    return time.perf_counter() - started, done.stdout.decode()


def main() -> int:
    print(machine.describe())
    with tempfile.TemporaryDirectory() as directory:
        var_dir = Path(directory)
        _manage(var_dir, "migrate", "--noinput", "-v0")
        _manage(var_dir, "seed_demo")
        cold, printed = _manage(var_dir, "check_stimuli")
        warm, _ = _manage(var_dir, "check_stimuli")
    clips = sum(int(n) for n in re.findall(r": (\d+) clips checked", printed))
    kinds = collections.Counter(
        kind for line in printed.splitlines() for text, kind in KIND.items() if text in line
    )
    print(
        f"demo studies: {clips} clips checked cold in {cold:.1f} s "
        f"({cold / max(clips, 1):.2f} s a clip, process start included), warm in {warm:.1f} s"
    )
    print("warnings by check: " + ", ".join(f"{k} {kinds[k]}" for k in KIND.values()))
    print(printed)
    return 0


if __name__ == "__main__":
    sys.exit(main())
