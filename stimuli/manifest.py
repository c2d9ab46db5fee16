"""A study's stimulus manifest: every clip with its parameters, facts and checksum.

The manifest (JSON, format ``signstudy.stimuli-manifest``) is enough to render the study
again, bit for bit: each entry holds the full :class:`~stimuli.clips.ClipSpec`, and the
file name is its content hash. :func:`generate` renders what is missing and skips what
exists, so a second run renders nothing.
"""

import json
import os
import tempfile
from dataclasses import asdict, dataclass
from pathlib import Path

from stimuli.clips import ClipError, ClipSpec, RenderedClip, file_sha256, render
from synthesis.formats import check_header
from synthesis.techniques import REGISTRY

FORMAT = "signstudy.stimuli-manifest"
FORMAT_VERSION = 1


@dataclass(frozen=True)
class Entry:
    """One clip of a manifest: its label (condition and item), spec and rendered facts."""

    label: str
    spec: ClipSpec
    clip: RenderedClip | None = None

    def to_dict(self) -> dict:
        data = {"label": self.label, "hash": self.spec.content_hash(), "spec": self.spec.to_dict()}
        # What each technique did, in words: a model's training and its provenance
        # travel with the clip (read back by nobody; the spec alone renders it again).
        data["techniques"] = REGISTRY.describe(self.spec.kind, self.spec.parameters)
        if self.clip is not None:
            facts = asdict(self.clip)
            facts["video"], facts["poster"] = self.clip.video.name, self.clip.poster.name
            data["clip"] = facts
        return data


def existing(spec: ClipSpec, directory: Path) -> RenderedClip | None:
    """Return the clip of *spec* if it was rendered into *directory* already, else None.

    A clip counts as rendered when its video and poster exist; the checksum is recorded
    from the file (the video is only ever moved into place whole).
    """
    from synthesis.render.video import count_frames

    name = spec.content_hash()
    video, poster = Path(directory) / f"{name}.mp4", Path(directory) / f"{name}.png"
    if not (video.is_file() and poster.is_file()):
        return None
    frames = count_frames(video)
    duration_ms = round(frames / spec.rate_hz * 1000)
    size = video.stat().st_size
    return RenderedClip(
        video, poster, duration_ms, frames, spec.width, spec.height, size, file_sha256(video)
    )


def generate(entries: list[Entry], directory: Path, progress=None) -> tuple[list[Entry], int]:
    """Render every entry missing from *directory*; return the entries with their clips
    and how many were rendered. *progress* receives (done, total, label) per clip."""
    done, rendered = [], 0
    for number, entry in enumerate(entries, start=1):
        clip = existing(entry.spec, directory)
        if clip is None:
            clip = render(entry.spec, directory)
            rendered += 1
        done.append(Entry(entry.label, entry.spec, clip))
        if progress is not None:
            progress(number, len(entries), entry.label)
    return done, rendered


def manifest_dict(
    entries: list[Entry], study: str = "", uploaded: list[dict] | None = None
) -> dict:
    """Return the manifest of *entries* as JSON-ready data.

    *uploaded* lists clips a study brings rather than renders (their files' names,
    SHA-256s and facts); they cannot be rendered again, so reading a manifest skips them.
    """
    data = {
        "format": FORMAT,
        "version": FORMAT_VERSION,
        "study": study,
        "clips": [entry.to_dict() for entry in entries],
    }
    if uploaded is not None:
        data["uploaded"] = uploaded
    return data


def write_manifest(
    entries: list[Entry], path: Path, study: str = "", uploaded: list[dict] | None = None
) -> Path:
    """Write the manifest as indented JSON, atomically (temporary file, then rename)."""
    path = Path(path)
    data = manifest_dict(entries, study, uploaded)
    path.parent.mkdir(parents=True, exist_ok=True)
    handle, temporary = tempfile.mkstemp(dir=path.parent, suffix=".json.part")
    with os.fdopen(handle, "w", encoding="utf-8") as out:
        json.dump(data, out, indent=1)
        out.write("\n")
    os.replace(temporary, path)
    return path


def read_manifest(path: Path) -> list[Entry]:
    """Read a manifest's entries (specs only); ClipError names what is wrong."""
    try:
        data = json.loads(Path(path).read_text(encoding="utf-8"))
    except (OSError, json.JSONDecodeError) as error:
        raise ClipError(f"{path}: cannot read the manifest ({error}).") from None
    check_header(data, FORMAT, FORMAT_VERSION, "stimuli manifest", ClipError, str(path))
    entries = []
    for number, clip in enumerate(data.get("clips") or [], start=1):
        spec = ClipSpec.from_dict(clip.get("spec") or {})
        if clip.get("hash") and clip["hash"] != spec.content_hash():
            raise ClipError(f"{path}: clip {number} does not match its recorded hash.")
        entries.append(Entry(str(clip.get("label", "")), spec))
    return entries
