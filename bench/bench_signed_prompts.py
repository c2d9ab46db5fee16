"""Time signing the ASL-first demo's prompts with the avatar, cold and from the cache.

Issue 35 (6): ``make demo`` signs five prompts of the spine study (studyplatform.demo.signed).
Figures: the cold render of the five clips and attaching them; a second database beside
the filled clips folder (the clips reused by their content hash, nothing re-rendered).
Runs in a fresh temporary data directory (SQLite). Prints figures; asserts nothing.

    .venv/bin/python bench/bench_signed_prompts.py
"""

import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import machine

ROOT = Path(__file__).resolve().parent.parent
SIGN = (
    "import time; from studyplatform.demo import sign_prompts; "
    "from studyplatform.models import Study; start = time.perf_counter(); "
    "n = sign_prompts(Study.objects.get(slug='spine-motion')); "
    "print(n, time.perf_counter() - start)"
)


def _manage(var_dir: Path, *arguments: str) -> str:
    unset = ("DATABASE_URL", "CELERY_BROKER_URL", "REDIS_URL")
    environment = {k: v for k, v in os.environ.items() if k not in unset}
    environment["SIGNSTUDY_VAR_DIR"] = str(var_dir)
    done = subprocess.run(
        [sys.executable, str(ROOT / "manage.py"), *arguments],
        check=True,
        env=environment,
        cwd=ROOT,
        capture_output=True,
        text=True,
    )
    return done.stdout


def _sign(var_dir: Path) -> tuple[int, float]:
    """Load the demo into an empty database and sign its prompts; return (signed, s)."""
    (var_dir / "signstudy.sqlite3").unlink(missing_ok=True)
    _manage(var_dir, "migrate", "--noinput", "-v0")
    _manage(var_dir, "seed_demo")
    signed, seconds = _manage(var_dir, "shell", "-c", SIGN).split()[-2:]
    return int(signed), float(seconds)


def main() -> None:
    print(machine.describe())
    with tempfile.TemporaryDirectory() as directory:
        var_dir = Path(directory)
        signed, cold = _sign(var_dir)
        clips = var_dir / "media" / "stimuli"
        stamps = {clip: clip.stat().st_mtime_ns for clip in clips.glob("*.mp4")}
        again, warm = _sign(var_dir)
        rewritten = sum(clip.stat().st_mtime_ns != stamp for clip, stamp in stamps.items())
    print(
        f"cold: {signed} prompts rendered and attached in {cold:.1f} s "
        f"({cold / max(signed, 1):.1f} s a prompt, the first with the engine's start-up)"
    )
    print(
        f"empty database, filled clips folder: {again} prompts attached in {warm:.1f} s, "
        f"{rewritten} of {len(stamps)} clip files rewritten; ratio to cold {warm / cold:.3f}"
    )


if __name__ == "__main__":
    started = time.perf_counter()
    main()
    print(f"({time.perf_counter() - started:.0f} s in all)")
