"""One stimulus clip: what determines its pixels, its content hash, and how to render it.

A :class:`ClipSpec` holds everything a clip's pixels depend on: the engine version and
the digests of the engine's data files (alphabet, letter routes, sign library), the
item, the condition's parameters, avatar view and side, size, frame rate and seed. Its
:meth:`~ClipSpec.content_hash` names the file, so a clip that exists is never rendered
twice and changing one parameter re-renders exactly the clips it touches.

Clip hygiene (spec 02/03 studies): every condition of an item is rendered with the same
camera, size and rate; fingerspelled words start and end on the relaxed hand and all
four timing conditions come from one (simulated) performance, time-warped, so only the
timing differs; sentences start and end at rest.
"""

import hashlib
import json
from dataclasses import asdict, dataclass, field
from functools import cache
from importlib import resources
from pathlib import Path

ENGINE_VERSION = "0.1.0"
DATA_FILES = ("asl_alphabet.yaml", "letter_routes.json", "signs.yaml")
WORD_CONDITIONS = ("mocap", "variable", "constant", "normalized", "simple")


class ClipError(ValueError):
    """A clip that cannot be specified or rendered as asked."""


@cache
def engine_digest() -> str:
    """Return a digest of the engine's version and data files (they shape every clip)."""
    digest = hashlib.sha256(ENGINE_VERSION.encode())
    for name in DATA_FILES:
        digest.update(resources.files("synthesis").joinpath("data", name).read_bytes())
    return digest.hexdigest()[:16]


@dataclass(frozen=True)
class ClipSpec:
    """Everything that determines one clip's pixels.

    *kind* is "word" (fingerspelled; *parameters* ``{"timing": …}``) or "sentence"
    (glosses; *parameters* ``{"spine": bool}``). *seed* fixes the simulated performance
    or the liveliness noise; it is per item, so the conditions of an item share it.
    """

    kind: str
    text: str
    parameters: dict = field(default_factory=dict)
    view: str = ""
    side: str = "right"
    width: int = 640
    height: int = 480
    rate_hz: float = 60.0
    seed: int = 0
    engine: str = field(default_factory=engine_digest)

    def __post_init__(self) -> None:
        if self.kind not in ("word", "sentence"):
            raise ClipError(f"A clip is of a word or a sentence, not {self.kind!r}.")
        if not self.view:
            object.__setattr__(self, "view", "hand" if self.kind == "word" else "upper-body")
        if self.kind == "word" and self.parameters.get("timing", "simple") not in WORD_CONDITIONS:
            raise ClipError(
                f"Unknown timing {self.parameters.get('timing')!r}; "
                f"use one of {', '.join(WORD_CONDITIONS)}."
            )

    def to_dict(self) -> dict:
        return asdict(self)

    @classmethod
    def from_dict(cls, data: dict) -> "ClipSpec":
        try:
            return cls(**data)
        except TypeError as error:
            raise ClipError(f"Malformed clip specification: {error}") from None

    def content_hash(self) -> str:
        """Return the SHA-256 of the canonical JSON of the specification."""
        canonical = json.dumps(self.to_dict(), sort_keys=True, separators=(",", ":"))
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


def file_sha256(path: Path) -> str:
    """Return the SHA-256 of a file's bytes."""
    digest = hashlib.sha256()
    with open(path, "rb") as handle:
        for block in iter(lambda: handle.read(1 << 20), b""):
            digest.update(block)
    return digest.hexdigest()


def _word_motion(spec: ClipSpec, avatar):
    """Return the avatar's motion for a fingerspelled word under its timing condition."""
    from synthesis.retarget import retarget
    from synthesis.timing import published_model
    from synthesis.timing.recordings import Recording, condition_timings, retime

    model = published_model()
    # One performance per item, shared by its conditions: only the timing differs.
    recording = Recording.simulate(spec.text, spec.seed, model, spec.side, spec.rate_hz)
    if spec.view != "hand":
        raise ClipError("Fingerspelled words render in the hand view for now.")
    timing = spec.parameters.get("timing", "mocap")
    if timing == "simple":
        from synthesis.spelling import spell

        return spell(spec.text, spec.side, spec.rate_hz)
    if timing == "mocap":
        motion = recording.motion
    else:
        motion = retime(recording, condition_timings(spec.text, model)[timing])
    return retarget(motion, avatar.rig)


def render(spec: ClipSpec, directory: Path, progress=None) -> RenderedClip:
    """Render *spec* into *directory* as ``<hash>.mp4`` and ``<hash>.png``.

    The video is written under a temporary name and moved into place (synthesis.render),
    so a crash leaves no file that looks finished.
    """
    from synthesis.render.clip import render_clip
    from synthesis.render.scene import hand_close_up, upper_body_front

    directory = Path(directory)
    directory.mkdir(parents=True, exist_ok=True)
    name = spec.content_hash()
    if spec.view == "hand":
        from synthesis.avatar.hand import hand_avatar

        avatar, camera = hand_avatar(spec.side), hand_close_up(spec.side)
    else:
        from synthesis.avatar.body import body_avatar

        avatar, camera = body_avatar(spec.side), upper_body_front(spec.side)
    if spec.kind == "word":
        motion = _word_motion(spec, avatar)
    else:
        from synthesis.sentence import SentenceOptions, synthesize

        spine = bool(spec.parameters.get("spine", True))
        options = SentenceOptions(spine=spine, rate_hz=spec.rate_hz, seed=spec.seed,
                                  dominant=spec.side)  # fmt: skip
        motion = synthesize(spec.text, options).dofs_rad
    video, poster = directory / f"{name}.mp4", directory / f"{name}.png"
    info = render_clip(avatar, motion, camera, video, spec.rate_hz, poster=poster,
                       width=spec.width, height=spec.height, progress=progress)  # fmt: skip
    return RenderedClip(
        video, poster, round(info.duration_s * 1000), info.n_frames, info.width, info.height,
        video.stat().st_size, file_sha256(video),
    )  # fmt: skip
