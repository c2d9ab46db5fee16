"""Tell what a stored file is by its content, and how it may be served.

Every file the platform keeps came from somebody: a researcher's upload or bundle, a
participant's webcam, the renderer. Its name proves nothing, so a file is known by its
first bytes (and, where that matters, by decoding it), stored under the extension its
content has, and served with the fixed type of that extension. Only the kinds below are
ever stored or served: no upload can become a page, a script, SVG or XML in a browser
(issue 33: an HTML "poster" in a bundle ran as the superuser who opened it).

Nothing here touches the database: the storages (:mod:`studyplatform.files.storage`) and the
models' validators use it while the app registry is still loading.
"""

import hashlib
import logging
import shutil
import struct
import subprocess
import tempfile
from contextlib import ExitStack, contextmanager
from dataclasses import dataclass
from pathlib import Path, PurePosixPath

from django.core.exceptions import ValidationError
from django.utils.deconstruct import deconstructible

logger = logging.getLogger(__name__)


@dataclass(frozen=True)
class MediaKind:
    """A kind of file the platform stores: its extension, served type and family."""

    suffix: str
    content_type: str
    family: str  # "video", "image", "motion" or "model"

    @property
    def inline(self) -> bool:
        """Whether a browser shows it in a page (a video or picture), else a download."""
        return self.family in ("video", "image")


WEBM = MediaKind(".webm", "video/webm", "video")
MP4 = MediaKind(".mp4", "video/mp4", "video")
PNG = MediaKind(".png", "image/png", "image")
JPEG = MediaKind(".jpg", "image/jpeg", "image")
WEBP = MediaKind(".webp", "image/webp", "image")
POSE = MediaKind(".pose", "application/octet-stream", "motion")
BVH = MediaKind(".bvh", "application/octet-stream", "motion")
GLB = MediaKind(".glb", "model/gltf-binary", "model")  # glTF 2.0 binary, VRM too
FBX = MediaKind(".fbx", "application/octet-stream", "motion")  # read through assimp

# What may be served, by the extension a stored file has. Files kept from before names
# followed content (.mov, .m4v, .jpeg uploads) are served as the container they claimed,
# which a browser only ever plays or shows: with nosniff it never reads them as a page.
SERVED = {kind.suffix: kind for kind in (WEBM, MP4, PNG, JPEG, WEBP, POSE, BVH, GLB, FBX)}
SERVED.update({".mov": MP4, ".m4v": MP4, ".jpeg": JPEG})

# The policy of every media response: nothing in it runs, even a file a browser renders
# as a document (sandbox gives it an opaque origin with scripts off).
MEDIA_CSP = (
    "default-src 'none'; img-src 'self'; media-src 'self'; style-src 'unsafe-inline'; sandbox"
)

EBML_MAGIC = b"\x1a\x45\xdf\xa3"  # Matroska / WebM
HEAD_BYTES = 64
DECODE_TIMEOUT_S = 60
# Chromium's MediaRecorder, busy, stamps two frames with the same millisecond; both
# decode, and only the null muxer the check writes to complains. Not a broken recording.
MUXER_TIMESTAMP_NOTE = "non monotonically increasing dts to muxer"


class MediaRejected(ValidationError):
    """A file that is not what it must be; the message says what it is not."""


def sniff(head: bytes) -> MediaKind | None:
    """Return the kind of a file from its first bytes (at least 16), None if it is none."""
    if head.startswith(EBML_MAGIC):
        return WEBM
    if head.startswith(b"glTF"):
        return GLB
    if head.startswith(b"Kaydara FBX Binary") or head.lstrip().startswith(b"; FBX"):
        return FBX
    if head[4:8] == b"ftyp":
        return MP4  # MP4, QuickTime and M4V: browsers play the ISO family as video/mp4
    if head.startswith(b"\x89PNG\r\n\x1a\n"):
        return PNG
    if head.startswith(b"\xff\xd8\xff"):
        return JPEG
    if head[:4] == b"RIFF" and head[8:12] == b"WEBP":
        return WEBP
    if head.lstrip(b"\xef\xbb\xbf \t\r\n").startswith(b"HIERARCHY"):
        return BVH
    if len(head) >= 4 and 0.0 < struct.unpack("<f", head[:4])[0] < 10.0 and b"<" not in head[:16]:
        return POSE  # pose-format's header opens with its version, a small float32
    return None


def sniff_file(file) -> MediaKind | None:
    """Return the kind of an open binary *file* (read from its start; position kept)."""
    position = file.tell()
    file.seek(0)
    head = file.read(HEAD_BYTES)
    file.seek(position)
    return sniff(head)


def safe_name(name: str, kind: MediaKind) -> str:
    """Return *name* with the extension of *kind* in place of whatever it had."""
    path = PurePosixPath(name)
    stem = path.stem.split(".")[0] or "file"
    return str(path.with_name(stem + kind.suffix))


def _ffmpeg(
    path: Path, *arguments: str, timeout_s: float = DECODE_TIMEOUT_S
) -> subprocess.CompletedProcess | None:
    from studyplatform.confine.ffmpeg import run_ffmpeg

    decode = ["-v", "error", "-i", str(path), "-map", "0:v:0", *arguments, "-f", "null", "-"]
    return run_ffmpeg(*decode, read=[path], timeout_s=timeout_s)


def decodes_as_video(path: Path) -> bool:
    """Return whether ffmpeg reads the file and decodes a first video frame from it."""
    done = _ffmpeg(path, "-frames:v", "1")
    return done is not None and done.returncode == 0


def remux_webm(source: Path, target: Path, video_only: bool = False) -> bool:
    """Copy a WebM's frames (its first video stream alone with *video_only*) into
    *target* with a duration and a seek index; return whether ffmpeg wrote it.

    A browser's MediaRecorder writes WebM as a live stream, without its length or cues,
    so a player shows 0:00 and cannot seek; remuxing (streams copied, nothing
    re-encoded, bit-exact headers) writes both.
    """
    from studyplatform.confine.ffmpeg import run_ffmpeg

    streams = "0:v:0" if video_only else "0"
    copy = ["-v", "error", "-y", "-i", str(source), "-map", streams, "-c", "copy"]
    copy += ["-fflags", "+bitexact", "-f", "webm", str(target)]
    done = run_ffmpeg(*copy, read=[source], write=[target.parent], timeout_s=DECODE_TIMEOUT_S)
    if done is None or done.returncode != 0:
        return False
    return target.is_file() and target.stat().st_size > 0


@contextmanager
def stored_video(upload, kind: MediaKind):
    """Yield (file, sha256) of an uploaded video as it is to be stored: a WebM remuxed
    (:func:`remux_webm`), any other video as it came; callers name it by the hash."""
    with tempfile.TemporaryDirectory() as folder, ExitStack() as opened:
        handle = upload
        if kind.suffix == ".webm":
            source, target = Path(folder) / "upload.webm", Path(folder) / "stored.webm"
            upload.seek(0)
            with open(source, "wb") as copy:
                shutil.copyfileobj(upload, copy)
            if remux_webm(source, target):
                handle = opened.enter_context(open(target, "rb"))
        digest = hashlib.sha256()
        handle.seek(0)
        for block in iter(lambda: handle.read(1 << 20), b""):
            digest.update(block)
        handle.seek(0)
        yield handle, digest.hexdigest()


def decoded_length(path: Path, timeout_s: float = DECODE_TIMEOUT_S) -> tuple[float, int] | None:
    """Decode the whole video; return its length in seconds and frames, None if any of it
    is broken.

    A recording cut short (its first third, say) still opens and shows a first frame;
    only decoding to the end finds that it ends before its data does.
    """
    done = _ffmpeg(path, "-progress", "pipe:1", "-nostats", timeout_s=timeout_s)
    complaints = (
        []
        if done is None
        else [
            line
            for line in done.stderr.decode(errors="replace").splitlines()
            if line.strip() and MUXER_TIMESTAMP_NOTE not in line
        ]
    )
    if done is None or done.returncode != 0 or complaints:
        # The participant is told to record again; the log says why, for the researcher.
        why = "timed out" if done is None else "; ".join(complaints)[-600:]
        logger.warning("%s does not decode to its end: %s", path.name, why)
        return None
    progress = dict(line.split(b"=", 1) for line in done.stdout.splitlines() if b"=" in line)
    try:
        duration_s, frames = int(progress[b"out_time_us"]) / 1e6, int(progress[b"frame"])
    except (KeyError, ValueError):  # "N/A": no frame came out
        return None
    return (duration_s, frames) if duration_s > 0 and frames > 0 else None


def decoded_duration_s(path: Path) -> float | None:
    """Decode the whole video; return its length in seconds, None if any of it is broken."""
    length = decoded_length(path)
    return None if length is None else length[0]


def image_is_whole(file) -> bool:
    """Return whether Pillow reads *file* as a PNG, JPEG or WebP picture to its end."""
    from PIL import Image

    position = file.tell()
    try:
        file.seek(0)
        with Image.open(file) as image:
            if image.format not in ("PNG", "JPEG", "WEBP"):
                return False
            image.verify()
        return True
    except Exception:  # Pillow raises many kinds for a broken picture
        return False
    finally:
        file.seek(position)


def check_kind(file, families: tuple[str, ...], what: str) -> MediaKind:
    """Return the kind of *file* if it is one of *families*, else raise MediaRejected."""
    kind = sniff_file(file)
    if kind is None or kind.family not in families:
        wanted = " or ".join(families)
        raise MediaRejected(f"{what} is not a {wanted} file (judged by its content).")
    return kind


def _upload_decodes(upload) -> bool:
    """Return whether an uploaded file (on disk or in memory) decodes as a video."""
    on_disk = getattr(upload, "temporary_file_path", None)
    if on_disk is not None:
        return decodes_as_video(Path(on_disk()))
    position = upload.tell()
    upload.seek(0)
    with tempfile.NamedTemporaryFile(suffix=".video") as copy:
        shutil.copyfileobj(upload, copy)
        copy.flush()
        upload.seek(position)
        return decodes_as_video(Path(copy.name))


def check_upload(upload, families: tuple[str, ...], what: str) -> MediaKind:
    """Return the kind of an uploaded file after checking it whole; MediaRejected if not.

    A picture must read to its end, a video decode a first frame; a motion file is
    parsed where it is used (its parser names what is wrong).
    """
    kind = check_kind(upload, families, what)
    if kind.family == "image" and not image_is_whole(upload):
        raise MediaRejected(f"{what} is not a whole PNG, JPEG or WebP picture.")
    if kind.family == "video" and not _upload_decodes(upload):
        raise MediaRejected(f"{what} does not decode as a video.")
    return kind


@deconstructible
class ContentValidator:
    """Validate a file field's new upload by content: one of *families*, whole."""

    def __init__(self, *families: str):
        self.families = families

    def __call__(self, value) -> None:
        if getattr(value, "_committed", True) or getattr(value, "file", None) is None:
            return  # a stored file: it was checked when it came in
        check_upload(value.file, self.families, f"“{value.name}”")

    def __eq__(self, other) -> bool:
        return isinstance(other, ContentValidator) and other.families == self.families
