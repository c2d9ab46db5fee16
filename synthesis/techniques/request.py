"""The one entry point from "an item under a condition" to its motion and its clip.

A :class:`ClipRequest` says everything a clip's pixels depend on besides the engine
itself: the item (kind and text), the techniques' parameters, and how it is filmed
(view, side, size, rate, seed). :func:`build_motion` runs the item kind and the
registered techniques over it; :func:`render_request` films the result. The command
line, :mod:`stimuli` and the platform all go through here, so no other module knows
which parameter means which motion.
"""

from collections.abc import Mapping
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import TYPE_CHECKING, Any, NoReturn

from synthesis.fingerspelling.alphabets import DEFAULT_ALPHABET
from synthesis.techniques.parameters import ClipError, Parameter

if TYPE_CHECKING:  # the pipeline's parts, imported where a clip is made
    import numpy as np

    from synthesis.avatar.looks import Look
    from synthesis.fingerspelling.word_timing import WordTiming
    from synthesis.rigs.body import BodyModel
    from synthesis.rigs.hand import HandModel
    from synthesis.signing.sentence import Sentence, SentenceOptions
    from synthesis.signing.signs import SignLibrary
    from synthesis.skeleton.kinematics import Pose
    from synthesis.timing.recordings import Recording
    from synthesis.transitions.lexicon import SignLexicon

VIEWS = ("hand", "upper-body")

REQUEST_PARAMETERS = (
    Parameter(
        "view",
        "choice",
        "hand",
        "Camera and avatar: the hand close-up or the upper body.",
        choices=VIEWS,
        labels={"hand": "hand close-up", "upper-body": "upper body"},
    ),
    Parameter("side", "choice", "right", "The signer's dominant hand.", choices=("right", "left")),
    Parameter("width", "int", 640, "Clip width.", minimum=16, maximum=3840, units="px"),
    Parameter("height", "int", 480, "Clip height.", minimum=16, maximum=2160, units="px"),
    Parameter("rate_hz", "float", 60.0, "Frame rate.", minimum=1, maximum=240, units="Hz"),
    Parameter(
        "seed",
        "int",
        0,
        "Seed of the item's performance and noise (shared by its conditions).",
        minimum=0,
        maximum=2**63 - 1,
    ),
)
FIELDS = tuple(p.name for p in REQUEST_PARAMETERS)


def _registry():
    from synthesis.techniques import REGISTRY

    return REGISTRY


@dataclass(frozen=True)
class ClipRequest:
    """An item under a condition, filmed one way: what determines a clip's pixels.

    *kind* is an item kind of the registry ("word", "sentence"); *parameters* the
    techniques' values, checked and completed with their defaults on creation; *view*
    defaults to the kind's; *width*/*height* in pixels (even), *rate_hz* frames per
    second; *seed* fixes the item's simulated performance and liveliness noise.
    """

    kind: str
    text: str
    parameters: Mapping[str, Any] = field(default_factory=dict)
    view: str = ""
    side: str = "right"
    width: int = 640
    height: int = 480
    rate_hz: float = 60.0
    seed: int = 0

    def __post_init__(self) -> None:
        item_kind = _registry().kind(self.kind)
        if not isinstance(self.text, str) or not self.text.strip():
            raise ClipError(f"A {item_kind.label} needs its text, not {self.text!r}.")
        if not self.view:
            object.__setattr__(self, "view", item_kind.default_view)
        for parameter in REQUEST_PARAMETERS:
            checked = parameter.check(getattr(self, parameter.name))
            object.__setattr__(self, parameter.name, checked)
        if self.view not in item_kind.views:
            raise ClipError(
                f"A {item_kind.label} renders in the {' or '.join(item_kind.views)} view, "
                f"not {self.view!r}."
            )
        if self.width % 2 or self.height % 2:
            raise ClipError(
                f"width and height must be even (H.264), not {self.width}×{self.height}."
            )
        object.__setattr__(self, "parameters", _registry().normalize(self.kind, self.parameters))

    @classmethod
    def from_parameters(
        cls, kind: str, text: str, parameters: Mapping[str, Any], **fields: Any
    ) -> "ClipRequest":
        """Return the request for *parameters* that may also hold the filming fields.

        A condition's or item's parameters are one flat mapping (``{"timing":
        "variable", "rate_hz": 30}``); *fields* are defaults the mapping overrides.
        """
        if not isinstance(parameters, Mapping):
            raise ClipError(f"Parameters must be a mapping of names to values, not {parameters!r}.")
        techniques = dict(parameters)
        for name in FIELDS:
            if name in techniques:
                fields[name] = techniques.pop(name)
        return cls(kind, text, techniques, **fields)

    def to_dict(self) -> dict[str, Any]:
        """Return the request as plain JSON values."""
        return {
            "kind": self.kind,
            "text": self.text,
            "parameters": dict(self.parameters),
            **{name: getattr(self, name) for name in FIELDS},
        }

    def files(self) -> list[Path]:
        """Return the files the techniques read (their content shapes the clip)."""
        declared = _registry().parameters(self.kind)
        return [
            Path(value)
            for name, value in sorted(self.parameters.items())
            if declared[name][0].type == "file" and value
        ]


def validate_parameters(kind: str, parameters: Mapping[str, Any]) -> dict[str, Any]:
    """Return *parameters* (techniques' and filming fields) checked for an item of *kind*.

    Raise :class:`ClipError` naming the first unknown key, wrong type, out-of-range value
    or technique that does not apply to *kind*. Only the keys given are returned.
    """
    # The request checks them as rendering would; the text plays no part in the check.
    request = ClipRequest.from_parameters(kind, "parameters", parameters)
    return {
        name: getattr(request, name) if name in FIELDS else request.parameters[name]
        for name in parameters
    }


@dataclass(frozen=True)
class Build:
    """A clip's motion in the making, passed from technique to technique.

    *performance* a recording to retime (words), *timing* a word's holds and transitions,
    *options* the sentence synthesis options, *library* a sign library, *motion* the
    result: DOF vectors (n_frames, n_dofs) of *rig*, or a Pose of its skeleton; *result*
    what the item kind made it from (a Sentence for sentences); *look* the avatar that
    films it (:class:`synthesis.avatar.looks.Look`; the default one when unset).
    """

    request: ClipRequest
    rig: "HandModel | BodyModel"
    performance: "Recording | None" = None
    timing: "WordTiming | None" = None
    options: "SentenceOptions | None" = None
    library: "SignLibrary | SignLexicon | None" = None
    motion: "np.ndarray | Pose | None" = None
    result: "Sentence | None" = None
    look: "Look | None" = None

    def but(self, **changes: Any) -> "Build":
        """Return a copy with *changes*."""
        return replace(self, **changes)

    @property
    def sentence_options(self) -> "SentenceOptions":
        """Return the sentence synthesis options (set when a sentence kind starts)."""
        if self.options is None:
            _not_made("sentence options")
        return self.options

    @property
    def sentence(self) -> "Sentence":
        """Return the sentence the motion was made from (set when a sentence finishes)."""
        if self.result is None:
            _not_made("sentence")
        return self.result

    @property
    def made_motion(self) -> "np.ndarray | Pose":
        """Return the finished motion (set when the item kind finishes)."""
        if self.motion is None:
            _not_made("motion")
        return self.motion


def _not_made(what: str) -> NoReturn:
    """Refuse a step that needs a part of the build an earlier step makes."""
    # A technique registered at a stage before the step that makes it: a bug in the
    # registry's order, not in the request.
    raise RuntimeError(f"The clip's {what} is not made yet at this step of the pipeline.")


def rig_for(view: str, side: str):
    """Return the rig of the avatar of *view*: the hand model or the upper body."""
    if view == "hand":
        from synthesis.rigs.hand import HandModel

        return HandModel(side)
    from synthesis.rigs.body import BodyModel

    return BodyModel(side)


def build_motion(request: ClipRequest) -> Build:
    """Return the motion of *request*: its kind starts, its techniques work, it finishes."""
    from synthesis.techniques.registry import MOTION, PREPARE

    registry = _registry()
    kind = registry.kind(request.kind)
    techniques = sorted(registry.for_kind(request.kind), key=lambda t: t.order)
    build = kind.start(Build(request, rig_for(request.view, request.side)))
    for technique in techniques:
        if technique.stage == PREPARE and technique.apply is not None:
            build = technique.apply(build)
    build = kind.finish(build)
    for technique in techniques:
        if technique.stage == MOTION and technique.apply is not None:
            build = technique.apply(build)
    return build


def avatar_and_camera(view: str, side: str, look=None, width: int = 640, height: int = 480):
    """Return the avatar of *view* in *look* (the default avatar when None) and the camera
    preset that films it at *width* × *height* (built once a process)."""
    from synthesis.avatar.looks import Look, avatar_for
    from synthesis.render.scene import hand_close_up, signing_view

    avatar = avatar_for(view, side, look or Look())
    if view == "hand":
        return avatar, hand_close_up(side)
    camera = signing_view(side, width, height)
    if look is not None and look.file:
        from synthesis.avatar.imported.load import fitted_camera

        camera = fitted_camera(camera, avatar)
    return avatar, camera


def filming(
    view: str,
    side: str,
    motion,
    rate_hz: float,
    width: int,
    height: int,
    word: str | None = None,
    look=None,
    alphabet: str = DEFAULT_ALPHABET,
):
    """Return the avatar of *view* (in *look*) and the camera that films *motion* (DOF
    vectors or a Pose): the close-up's follows the hand (:mod:`synthesis.render.follow`)
    at the scale that fits every letter of *word* in *alphabet* (so all conditions of a
    word share it) and from the rest pose's framing at both ends; the signing view's
    stands still."""
    avatar, camera = avatar_and_camera(view, side, look, width, height)
    if view == "hand":
        import numpy as np

        from synthesis.fingerspelling.alphabet import letter, rest_pose
        from synthesis.fingerspelling.spelling import word_letters
        from synthesis.render.follow import follow_hand

        # The word's letters are solved for spelling it anyway; the whole alphabet
        # would cost every render process seconds.
        letters = None
        if word:
            shapes = [letter(c, side, alphabet) for c in word_letters(word, alphabet)]
            # A J's or Z's path keys too: the camera keeps a path in view from one place.
            letters = np.vstack(
                [s.dofs_rad if s.path_rad is None else s.path_rad for s in shapes]
                + [rest_pose(side)[None]]
            )
        camera = follow_hand(
            avatar,
            motion,
            camera,
            rate_hz,
            width,
            height,
            scale_poses=letters,
            rest_pose=rest_pose(side),
        )
    return avatar, camera


def film(request: ClipRequest, build: Build):
    """Return the avatar and camera that film *build*'s motion as *request* asks."""
    word = request.text if request.kind == "word" else None
    return filming(
        request.view,
        request.side,
        build.motion,
        request.rate_hz,
        request.width,
        request.height,
        word,
        build.look,
        request.parameters.get("alphabet", DEFAULT_ALPHABET),
    )


def render_request(
    request: ClipRequest,
    out: str | Path,
    poster: str | Path | None = None,
    progress=None,
    workers: int = 1,
    build: Build | None = None,
    filmed=None,
):
    """Render *request* to an MP4 at *out* (and a poster PNG); return the video's facts.

    *build* is the request's motion and *filmed* its (avatar, camera), when the caller
    made them already.
    """
    from synthesis.render.clip import render_clip

    build = build or build_motion(request)
    avatar, camera = filmed or film(request, build)
    return render_clip(
        avatar,
        build.made_motion,
        camera,
        out,
        request.rate_hz,
        poster=poster,
        width=request.width,
        height=request.height,
        progress=progress,
        workers=workers,
    )
