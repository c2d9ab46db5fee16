"""Time an uploaded clip's check and conversion for browsers (issue 37).

    .venv/bin/python bench/bench_uploads.py

For a 10-second test pattern at 640×480 and 1280×720, 30 fps: an H.264 MP4 with its
index first (kept byte for byte), the same in a MOV (rewrapped), and MPEG-4 part 2 in a
MOV (re-encoded as H.264): the time to decode it to its end, convert it and cut its
poster (studyplatform.files.video_files.prepare_clip), against the clip's own length.
"""

import subprocess
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

import imageio_ffmpeg
import machine

from studyplatform.files.video_files import prepare_clip

SECONDS = 10


def make(folder: Path, size: str, codec: str, container: str) -> Path:
    out = folder / f"{size}-{codec}.{container}"
    extra = ["-pix_fmt", "yuv420p"] if codec == "libx264" else []
    if container == "mp4":
        extra += ["-movflags", "+faststart"]
    subprocess.run(
        [
            imageio_ffmpeg.get_ffmpeg_exe(),
            "-v",
            "error",
            "-y",
            "-f",
            "lavfi",
            "-i",
            f"testsrc2=size={size}:rate=30",
            "-t",
            str(SECONDS),
            "-c:v",
            codec,
            *extra,
            str(out),
        ],
        check=True,
    )
    return out


def main() -> int:
    print(machine.describe())
    with tempfile.TemporaryDirectory() as folder:
        folder = Path(folder)
        for size in ("640x480", "1280x720"):
            for codec, container in (("libx264", "mp4"), ("libx264", "mov"), ("mpeg4", "mov")):
                source = make(folder, size, codec, container)
                work = folder / f"work-{size}-{codec}-{container}"
                work.mkdir()
                started = time.perf_counter()
                clip = prepare_clip(source, work, source.name)
                seconds = time.perf_counter() - started
                how = clip.converted or "kept"
                print(
                    f"{size} {codec:7s} in {container.upper()}: {how:10s} {seconds:5.2f} s "
                    f"for a {SECONDS} s clip ({SECONDS / seconds:4.1f}× real time), "
                    f"{clip.size_bytes / 1e6:.1f} MB"
                )
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
