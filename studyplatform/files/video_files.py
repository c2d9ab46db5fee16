"""Make a researcher's video a clip every browser plays: checked, converted, posted.

An uploaded clip is decoded to its end (a file cut short is refused), its facts read
(codec, size, frame rate, length), and stored as browsers play it: an H.264 MP4 whose
index comes first (``faststart``, so playback starts before the whole file is in) or a
WebM with its duration and seek index. A file that already is one is kept byte for
byte; an H.264 file in another container or with its index last is remuxed (frames
copied, nothing re-encoded); anything else is re-encoded as H.264 (imageio-ffmpeg's
ffmpeg, libx264, CRF 18). Audio is dropped: clips play muted. Its first frame is the
poster. Nothing here touches the database.
"""

import shutil
import struct
from dataclasses import dataclass
from pathlib import Path

from stimuli.clips import file_sha256
from studyplatform.files.media_types import (
    MP4,
    WEBM,
    MediaRejected,
    decoded_length,
    remux_webm,
    sniff,
)

MAX_CLIP_BYTES = 500 * 1024**2
MAX_CLIP_S = 600.0
MAX_SIDE_PX = 4096
CONVERT_TIMEOUT_S = 900
H264_PIXELS = ("yuv420p", "yuvj420p")
WEBM_CODECS = ("vp8", "vp9", "av1")
H264_ARGUMENTS = (
    "-c:v",
    "libx264",
    "-preset",
    "medium",
    "-crf",
    "18",
    "-pix_fmt",
    "yuv420p",
    # H.264 in 4:2:0 needs even sides; a one-pixel crop keeps every other pixel as it was.
    "-vf",
    "crop=trunc(iw/2)*2:trunc(ih/2)*2",
)


@dataclass(frozen=True)
class PreparedClip:
    """A clip ready to store: its playable video, poster and facts."""

    video: Path
    poster: Path
    suffix: str
    sha256: str
    source_sha256: str
    source_codec: str
    converted: str  # "", "remuxed" or "transcoded"
    duration_ms: int
    frame_count: int
    frame_rate: float
    width: int
    height: int
    size_bytes: int


def _stream_facts(path: Path, what: str) -> dict:
    """Return ffmpeg's description of the file's first video stream."""
    from studyplatform.confine.ffmpeg import stream_facts

    facts = stream_facts(path)
    if facts is None:
        raise MediaRejected(f"{what} does not decode as a video.")
    # ffmpeg's own words, as imageio-ffmpeg reads them: "vp8," or "yuv420p(tv, progressive)".
    facts["codec"] = str(facts.get("codec", "")).split(",")[0].strip()
    facts["pix_fmt"] = str(facts.get("pix_fmt", "")).split("(")[0].strip()
    return facts


def _index_first(path: Path) -> bool:
    """Return whether an MP4's index (``moov``) comes before its frames (``mdat``)."""
    with open(path, "rb") as handle:
        while header := handle.read(8):
            if len(header) < 8:
                return False
            size, box = struct.unpack(">I4s", header)
            if box in (b"moov", b"mdat"):
                return box == b"moov"
            if size == 1:  # a 64-bit size follows
                size = struct.unpack(">Q", handle.read(8))[0] - 8
            elif size < 8:
                return False
            handle.seek(size - 8, 1)
    return False


def _is_quicktime(path: Path) -> bool:
    with open(path, "rb") as handle:
        return handle.read(12)[8:12] == b"qt  "


def _run(*arguments: str, source: Path, folder: Path) -> bool:
    """Run ffmpeg reading *source* and writing into *folder*; return whether it did."""
    from studyplatform.confine.ffmpeg import run_ffmpeg

    done = run_ffmpeg(
        "-v", "error", "-y", *arguments, read=[source], write=[folder], timeout_s=CONVERT_TIMEOUT_S
    )
    return done is not None and done.returncode == 0


def _playable(source: Path, folder: Path, suffix: str, facts: dict) -> tuple[Path, str, str]:
    """Return (file, suffix, how converted) of *source* as browsers play it."""
    codec, pixels = facts["codec"], facts["pix_fmt"]
    if suffix == WEBM.suffix and codec in WEBM_CODECS:
        target = folder / "clip.webm"
        if remux_webm(source, target, video_only=True):
            same = file_sha256(target) == file_sha256(source)
            return (source, suffix, "") if same else (target, suffix, "remuxed")
    h264 = codec == "h264" and pixels in H264_PIXELS
    if h264 and suffix == MP4.suffix and _index_first(source) and not _is_quicktime(source):
        return source, MP4.suffix, ""
    target = folder / "clip.mp4"
    into = ["-movflags", "+faststart", "-f", "mp4", str(target)]
    if h264 and _run(
        "-i", str(source), "-map", "0:v:0", "-c", "copy", *into, source=source, folder=folder
    ):
        return target, MP4.suffix, "remuxed"
    if _run(
        "-i", str(source), "-map", "0:v:0", *H264_ARGUMENTS, *into, source=source, folder=folder
    ):
        return target, MP4.suffix, "transcoded"
    raise MediaRejected("could not be converted to a video browsers play.")


def prepare_clip(source: Path, folder: Path, what: str) -> PreparedClip:
    """Check the uploaded video at *source* and make it playable in *folder*.

    Raise MediaRejected naming *what* and the problem: not a video by its content, over
    500 MB, not decoding to its end, longer than 10 minutes, larger than 4096 pixels a side.
    """
    size = source.stat().st_size
    if size > MAX_CLIP_BYTES:
        raise MediaRejected(f"{what} is larger than {MAX_CLIP_BYTES // 1024**2} MB.")
    with open(source, "rb") as handle:
        kind = sniff(handle.read(64))
    if kind is None or kind.family != "video":
        raise MediaRejected(f"{what} is not a video (MP4, WebM or MOV), judged by its content.")
    facts = _stream_facts(source, what)
    width, height = facts.get("source_size") or facts.get("size") or (0, 0)
    if max(width, height) > MAX_SIDE_PX:
        raise MediaRejected(f"{what} is {width}×{height} pixels; at most {MAX_SIDE_PX} a side.")
    length = decoded_length(source, timeout_s=CONVERT_TIMEOUT_S)
    if length is None:
        raise MediaRejected(f"{what} does not decode to its end (a broken or cut-off file).")
    if length[0] > MAX_CLIP_S:
        raise MediaRejected(
            f"{what} lasts {length[0]:.0f} s; a clip may last "
            f"{MAX_CLIP_S / 60:.0f} minutes at most."
        )
    try:
        video, suffix, converted = _playable(source, folder, kind.suffix, facts)
    except MediaRejected as error:
        raise MediaRejected(f"{what} {error.messages[0]}") from None
    if converted:
        length = decoded_length(video, timeout_s=CONVERT_TIMEOUT_S) or length
        width, height = _stream_facts(video, what).get("size", (width, height))
    poster = folder / "poster.png"
    if not _run(
        "-i",
        str(video),
        "-map",
        "0:v:0",
        "-frames:v",
        "1",
        str(poster),
        source=video,
        folder=folder,
    ):
        raise MediaRejected(f"{what}: no first frame could be read for its poster.")
    duration_s, frames = length
    frame_rate = float(facts.get("fps") or frames / duration_s)
    return PreparedClip(
        video=video,
        poster=poster,
        suffix=suffix,
        sha256=file_sha256(video),
        source_sha256=file_sha256(source),
        source_codec=facts["codec"][:40],
        converted=converted,
        duration_ms=round(duration_s * 1000),
        frame_count=frames,
        frame_rate=round(frame_rate, 3),
        width=int(width),
        height=int(height),
        size_bytes=video.stat().st_size,
    )


def copy_upload(upload, target: Path) -> Path:
    """Write an uploaded file (Django's, or any binary file object) to *target*."""
    upload.seek(0)
    with open(target, "wb") as copy:
        shutil.copyfileobj(upload, copy)
    return target
