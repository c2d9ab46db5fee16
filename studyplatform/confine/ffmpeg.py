"""Run ffmpeg on an uploaded video confined: local files only, bounded, few files.

Every ffmpeg the platform runs goes through :func:`run_ffmpeg`: each input is read with
``-protocol_whitelist file,pipe`` (an HLS or concat playlist disguised as a video names
no other file or URL), inside the jail with the caller's files alone readable and its
output folder alone writable, under :data:`~studyplatform.confine.runner.MEDIA`'s limits.
"""

import subprocess
from dataclasses import replace
from pathlib import Path

from studyplatform.confine.runner import MEDIA, ConfinedError, Limits, confined_run

PROTOCOLS = "file,pipe"


def ffmpeg_command(arguments: list[str]) -> list[str]:
    """Return ffmpeg's command line for *arguments*, each input limited to local files."""
    import imageio_ffmpeg

    command = [imageio_ffmpeg.get_ffmpeg_exe(), "-nostdin", "-hide_banner"]
    for argument in arguments:
        if argument == "-i":
            command += ["-protocol_whitelist", PROTOCOLS]
        command.append(argument)
    return command


def run_ffmpeg(
    *arguments: str,
    read: list[Path],
    write: list[Path] = (),
    timeout_s: float | None = None,
    limits: Limits = MEDIA,
) -> subprocess.CompletedProcess | None:
    """Run ffmpeg with *arguments* confined to reading *read* and writing into *write*
    (folders or files); return what it printed, or None when it ran out of time or was
    stopped at a limit (the callers treat that as a file that does not decode)."""
    if timeout_s is not None:
        limits = replace(limits, wall_s=timeout_s, cpu_s=int(timeout_s) + 1)
    try:
        return confined_run(ffmpeg_command(list(arguments)), read=read, write=write, limits=limits)
    except ConfinedError:
        return None


def stream_facts(path: Path) -> dict | None:
    """Return ffmpeg's description of the first video stream of *path* (codec, pixel
    format, size, frame rate, duration), or None when it describes none."""
    from imageio_ffmpeg._parsing import parse_ffmpeg_header

    done = run_ffmpeg("-i", str(path), read=[path], timeout_s=60)
    if done is None:
        return None
    text = done.stderr.decode(errors="replace")
    if " Video: " not in text:
        return None
    try:
        return parse_ffmpeg_header(text)
    except (ValueError, IndexError, KeyError):
        return None
