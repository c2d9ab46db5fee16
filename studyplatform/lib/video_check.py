"""Tell whether an uploaded file is a video a browser recorded: WebM or MP4 that decodes.

The container's magic bytes alone let a WebM or MP4 header followed by anything (an HTML
page, say) through as a "video"; ffmpeg (the one imageio-ffmpeg ships) must read the
container and decode its first frame.
"""

import subprocess
from pathlib import Path

# The containers browsers record into: WebM (Matroska's EBML magic) and MP4 (Safari).
EBML_MAGIC = b"\x1a\x45\xdf\xa3"
MP4_BRAND_AT = slice(4, 8)
DECODE_TIMEOUT_S = 60


def container_suffix(path: Path) -> str | None:
    """Return ".webm" or ".mp4" by the file's first bytes, None for anything else."""
    with open(path, "rb") as handle:
        head = handle.read(12)
    if head.startswith(EBML_MAGIC):
        return ".webm"
    if head[MP4_BRAND_AT] == b"ftyp":
        return ".mp4"
    return None


def decodes_as_video(path: Path) -> bool:
    """Return whether ffmpeg reads the file and decodes a first video frame from it."""
    import imageio_ffmpeg

    command = [imageio_ffmpeg.get_ffmpeg_exe(), "-nostdin", "-v", "error", "-i", str(path),
               "-map", "0:v:0", "-frames:v", "1", "-f", "null", "-"]  # fmt: skip
    try:
        done = subprocess.run(command, capture_output=True, timeout=DECODE_TIMEOUT_S)
    except subprocess.TimeoutExpired:
        return False
    return done.returncode == 0
