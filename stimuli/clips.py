"""One stimulus clip: what determines its pixels, its content hash, and how to render it.

A :class:`ClipSpec` holds everything a clip's pixels depend on: the digest of the
engine's source and data files (:func:`synthesis.identity.engine_digest`), the item, the
condition's parameters, avatar view and side, size, frame rate and seed. Its
:meth:`~ClipSpec.content_hash` names the file, so a clip that exists is never rendered
twice and changing one parameter re-renders exactly the clips it touches.

Clip hygiene (spec 02/03 studies): every condition of an item is rendered with the same
camera, size and rate; fingerspelled words start and end on the relaxed hand and all
four timing conditions come from one (simulated) performance, time-warped, so only the
timing differs; sentences start and end at rest.
"""

import hashlib
import json
from dataclasses import dataclass, field
from pathlib import Path

from stimuli.quality import checked
from synthesis.identity import engine_digest, file_sha256
from synthesis.techniques import REGISTRY, ClipError, ClipRequest, build_motion, render_request
from synthesis.techniques.request import film

__all__ = [
    "ClipError",
    "ClipSpec",
    "RenderedClip",
    "clip_files",
    "engine_digest",
    "file_sha256",
    "render",
    "rendered",
]


@dataclass(frozen=True)
class ClipSpec(ClipRequest):
    """Everything that determines one clip's pixels: a clip request and the engine's digest.

    The request's fields (*kind*, *text*, *parameters*, view, side, size, rate, seed) are
    checked and completed with defaults on creation, so ``{"timing": "variable"}`` and
    the same with every default spelled out name one clip; *engine* is the digest of
    the engine's source and data files. *seed* fixes the simulated performance or the
    liveliness noise; it is per item, so the conditions of an item share it.
    """

    engine: str = field(default_factory=engine_digest)

    @classmethod
    def from_request(cls, request: ClipRequest, engine: str | None = None) -> "ClipSpec":
        """Return the specification of *request* rendered by this engine (or *engine*);
        ClipError names a text the request cannot sign (a letter its alphabet lacks)
        before anything is queued to render it."""
        REGISTRY.check_text(request.kind, request.text, request.parameters)
        values = request.to_dict()
        if engine:
            values["engine"] = engine
        return cls(**values)

    def to_dict(self) -> dict:
        return {**super().to_dict(), "engine": self.engine}

    @classmethod
    def from_dict(cls, data: dict) -> "ClipSpec":
        try:
            return cls(**data)
        except TypeError as error:
            raise ClipError(f"Malformed clip specification: {error}") from None

    def content_hash(self) -> str:
        """Return the SHA-256 of the canonical JSON of the specification.

        The files it names (a recording, a model, a library) count by their content.
        """
        data = self.to_dict()
        files = {str(path): file_sha256(path) for path in self.files()}
        if files:
            data["files"] = files
        canonical = json.dumps(data, sort_keys=True, separators=(",", ":"))
        return hashlib.sha256(canonical.encode()).hexdigest()


@dataclass(frozen=True)
class RenderedClip:
    """A rendered clip's files and facts."""

    video: Path
    poster: Path
    duration_ms: int
    frame_count: int
    width: int
    height: int
    size_bytes: int
    sha256: str


def render(spec: ClipSpec, directory: Path, progress=None) -> RenderedClip:
    """Render *spec* into *directory* as ``<hash>.mp4``, ``<hash>.png`` and ``<hash>.json``.

    The motion's stimulus check is kept beside it (``<hash>.quality.json``,
    :mod:`stimuli.quality`). A clip already rendered there (by any study, version or
    database) is returned as it is, never rendered again or overwritten
    (:func:`rendered`). The video is written under a temporary name and moved into
    place (synthesis.render), so a crash leaves no file that looks finished; the facts
    file is written last.
    """
    directory = Path(directory)
    name = spec.content_hash()
    found = rendered(spec, directory, name)
    if found is not None:
        return found
    directory.mkdir(parents=True, exist_ok=True)
    video, poster, facts = clip_files(directory, name)
    build = build_motion(spec)
    # The check and the render share the motion and its filming (a close-up's camera
    # follows the hand: solving it twice doubled that work).
    filmed = film(spec, build)
    checked(spec, directory, name, build, filmed)
    info = render_request(spec, video, poster=poster, progress=progress, build=build, filmed=filmed)
    clip = RenderedClip(
        video,
        poster,
        round(info.duration_s * 1000),
        info.n_frames,
        info.width,
        info.height,
        video.stat().st_size,
        file_sha256(video),
    )
    _write_facts(clip, facts, name)
    return clip


def clip_files(directory: Path, content_hash: str) -> tuple[Path, Path, Path]:
    """Return the video, poster and facts files of the clip named *content_hash*."""
    directory = Path(directory)
    video, poster, facts = (directory / f"{content_hash}{ext}" for ext in (".mp4", ".png", ".json"))
    return video, poster, facts


def rendered(
    spec: ClipSpec, directory: Path, content_hash: str | None = None
) -> RenderedClip | None:
    """Return the clip of *spec* already in *directory*, or None if it must be rendered.

    The files are named by the content hash, so they are the clip whoever rendered them.
    Its facts come from ``<hash>.json``; a clip rendered before facts were kept has its
    video measured once (ffmpeg) and the facts written. A video whose size or SHA-256
    is not the recorded one is not reused. *content_hash* is the spec's, where the caller
    has it already (it reads the files the spec names).
    """
    name = content_hash or spec.content_hash()
    video, poster, facts = clip_files(directory, name)
    if not (video.is_file() and poster.is_file()):
        return None
    if facts.is_file():
        try:
            data = json.loads(facts.read_text())
            clip = RenderedClip(
                video,
                poster,
                int(data["duration_ms"]),
                int(data["frame_count"]),
                int(data["width"]),
                int(data["height"]),
                int(data["size_bytes"]),
                str(data["sha256"]),
            )
        except (ValueError, KeyError, TypeError):
            return None
        if data.get("content_hash") != name or video.stat().st_size != clip.size_bytes:
            return None
        return clip if file_sha256(video) == clip.sha256 else None
    clip = _measure(video, poster)
    _write_facts(clip, facts, name)
    return clip


def _measure(video: Path, poster: Path) -> RenderedClip:
    import imageio_ffmpeg

    frames = imageio_ffmpeg.read_frames(str(video))
    meta = next(frames)
    frames.close()
    n_frames, _ = imageio_ffmpeg.count_frames_and_secs(str(video))
    width, height = meta["size"]
    duration_ms = round(n_frames / meta["fps"] * 1000)
    return RenderedClip(
        video,
        poster,
        duration_ms,
        n_frames,
        width,
        height,
        video.stat().st_size,
        file_sha256(video),
    )


def _write_facts(clip: RenderedClip, path: Path, name: str) -> None:
    """Write a clip's facts next to it, atomically (a temporary file, then rename)."""
    facts = {
        "content_hash": name,
        "duration_ms": clip.duration_ms,
        "frame_count": clip.frame_count,
        "width": clip.width,
        "height": clip.height,
        "size_bytes": clip.size_bytes,
        "sha256": clip.sha256,
    }
    temporary = path.with_suffix(".json.part")
    temporary.write_text(json.dumps(facts, indent=2) + "\n")
    temporary.replace(path)
