"""Time rendering the demo studies' stimuli: cold, warm, and 1 against 2 workers.

Targets (issue 6): the cold render of the full demo set in < 6 min on this 2-core
machine; a warm re-run in < 10 s; the speed-up of 2 workers over 1. Issue 35: loading
the demo on an empty database beside the filled media folder renders nothing. Runs in a fresh
temporary data directory (SQLite, no broker: local rendering processes). Prints
figures; asserts nothing.

    .venv/bin/python bench/bench_stimuli.py [--skip-single]
"""

import argparse
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import machine

ROOT = Path(__file__).resolve().parent.parent
STUDIES = ("fingerspelling-timing", "spine-motion")


def _manage(var_dir: Path, *arguments: str) -> float:
    """Run manage.py in *var_dir*; return the wall time in seconds."""
    unset = ("DATABASE_URL", "CELERY_BROKER_URL", "REDIS_URL")  # SQLite, local rendering
    environment = {k: v for k, v in os.environ.items() if k not in unset}
    environment["SIGNSTUDY_VAR_DIR"] = str(var_dir)
    started = time.perf_counter()
    command = [sys.executable, str(ROOT / "manage.py"), *arguments]
    subprocess.run(command, check=True, env=environment, cwd=ROOT, stdout=subprocess.DEVNULL)
    return time.perf_counter() - started


def _cold(workers: int) -> tuple[float, dict]:
    with tempfile.TemporaryDirectory() as directory:
        var_dir = Path(directory)
        _manage(var_dir, "migrate", "--noinput", "-v0")
        _manage(var_dir, "seed_demo")
        per_study = {
            slug: _manage(var_dir, "generate_stimuli", slug, "--workers", str(workers))
            for slug in STUDIES
        }
        warm = sum(_manage(var_dir, "generate_stimuli", slug) for slug in STUDIES)
        clips = list((var_dir / "media" / "stimuli").glob("*.mp4"))
        # Issue 35: an empty database beside the filled media folder (a fresh install, a
        # move to PostgreSQL) reuses every clip by its content hash.
        stamps = {clip: clip.stat().st_mtime_ns for clip in clips}
        (var_dir / "signstudy.sqlite3").unlink()
        fresh = _manage(var_dir, "migrate", "--noinput", "-v0")
        fresh += _manage(var_dir, "seed_demo")
        fresh += sum(_manage(var_dir, "generate_stimuli", slug) for slug in STUDIES)
        rewritten = sum(clip.stat().st_mtime_ns != stamp for clip, stamp in stamps.items())
        facts = {
            "per_study": per_study,
            "warm": warm,
            "clips": len(clips),
            "fresh": fresh,
            "rewritten": rewritten,
        }
        return sum(per_study.values()), facts


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--skip-single", action="store_true", help="only the 2-worker run")
    args = parser.parse_args()
    print(machine.describe())
    two, facts = _cold(2)
    print(
        f"cold render, 2 workers: {facts['clips']} clips in {two:.0f} s "
        f"({', '.join(f'{k} {v:.0f} s' for k, v in facts['per_study'].items())}; "
        f"target < 360 s)"
    )
    print(f"warm re-run (nothing to render): {facts['warm']:.1f} s (target < 10 s)")
    print(
        f"empty database, filled media folder (migrate, seed_demo, generate): "
        f"{facts['fresh']:.1f} s, {facts['rewritten']} of {facts['clips']} clip files "
        f"rewritten; ratio to the cold render {facts['fresh'] / two:.3f}"
    )
    if not args.skip_single:
        one, _ = _cold(1)
        print(f"cold render, 1 worker: {one:.0f} s; speed-up with 2 workers: {one / two:.2f}×")


if __name__ == "__main__":
    main()
