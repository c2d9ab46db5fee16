"""The signer who films a clip: the human avatar (a body, a skin tone) or the simple one.

Changes no motion: the same DOFs play on either avatar (both are skinned to the
engine's rig), so a study can compare avatars as it compares techniques (issue 36).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from synthesis.avatar.human.build import DEFAULT_SKIN_TONE, SKIN_TONES
from synthesis.avatar.human.phenotype import ADULT_AGE, CUSTOM, DEFAULT_PRESET, PRESETS, RAW_VALUES
from synthesis.avatar.looks import AVATARS, Look
from synthesis.techniques.kinds import SIGNED, WORD
from synthesis.techniques.parameters import ClipError, Parameter
from synthesis.techniques.registry import Technique

if TYPE_CHECKING:
    from synthesis.techniques.request import Build


# MakeHuman's default human: each macro value a custom body leaves as it is.
RAW_DEFAULT = 0.5


def _raw(values) -> tuple[tuple[str, float], ...]:
    # The parameters are body_<value>: "height" alone is the clip's.
    given = {name: values[f"body_{name}"] for name in RAW_VALUES}
    return tuple((name, value) for name, value in given.items() if value != RAW_DEFAULT)


def _look(values) -> Look:
    return Look(
        values["avatar"], values["body"], values["skin_tone"], _raw(values), values["avatar_file"]
    )


def _apply(build: Build) -> Build:
    look = _look(build.request.parameters)
    if look.file:
        from synthesis.avatar.imported.gltf_read import GltfError
        from synthesis.avatar.imported.load import check_body, check_fingers

        try:
            if build.request.view != "hand":  # a hand on its own has no arms to turn
                check_body(look.file)
            if build.request.kind == WORD.name:
                check_fingers(look.file, build.request.side)
        except GltfError as error:
            raise ClipError(str(error)) from None
    return build.but(look=look)


def _check(values) -> None:
    raw = _raw(values)
    if values["avatar_file"] and (
        values["avatar"] != "human"
        or values["body"] != DEFAULT_PRESET
        or values["skin_tone"] != DEFAULT_SKIN_TONE
        or raw
    ):
        raise ClipError(
            "avatar_file films the clip with its own avatar: leave avatar, body, "
            "skin_tone and the macro values at their defaults."
        )
    if values["avatar"] == "simple" and (
        values["body"] != DEFAULT_PRESET or values["skin_tone"] != DEFAULT_SKIN_TONE or raw
    ):
        raise ClipError(
            "The simple avatar has one body and skin tone; body, skin_tone and "
            "the macro values choose the human avatar's."
        )
    if raw and values["body"] != CUSTOM:
        given = ", ".join(f"body_{name}" for name, _ in raw)
        raise ClipError(
            f"{given} shape a body only when body is {CUSTOM}; {values['body']} is a preset."
        )


def _summary(values) -> str:
    if values["avatar_file"]:
        return f"imported avatar {values['avatar_file'].rsplit('/', 1)[-1]}"
    if values["avatar"] == "simple":
        return "simple avatar"
    body = values["body"]
    if body == CUSTOM:
        body = ", ".join(f"{name} {value:g}" for name, value in _raw(values)) or "MakeHuman default"
        body = f"custom body: {body}"
    return f"human signer ({body}, {values['skin_tone']} skin)"


def _macro(name: str, help: str, minimum: float = 0.0) -> Parameter:
    help = f"{help} (a custom body only; MakeHuman's macro value, {RAW_DEFAULT:g} its default)."
    return Parameter(f"body_{name}", "float", RAW_DEFAULT, help, minimum=minimum, maximum=1.0)


TECHNIQUE = Technique(
    name="avatar",
    chooses_content=True,
    label="Avatar",
    kinds=frozenset({WORD.name, *SIGNED}),
    parameters=(
        Parameter(
            "avatar",
            "choice",
            "human",
            "human: a realistic signer built from MakeHuman's CC0 body (face with ARKit "
            "expressions, eyes, brows, hair, a long-sleeved top); simple: the engine's "
            "first avatar, meshed from round cones (studies made with it keep its look).",
            choices=AVATARS,
            labels={"human": "human signer", "simple": "simple avatar"},
        ),
        Parameter(
            "body",
            "choice",
            DEFAULT_PRESET,
            f"The human signer's body, a MakeHuman preset (gender, age, build): "
            f"{', '.join(PRESETS)}; or {CUSTOM}, shaped by the macro values below.",
            choices=(*PRESETS, CUSTOM),
        ),
        Parameter(
            "skin_tone",
            "choice",
            DEFAULT_SKIN_TONE,
            "The human signer's skin tone; the top's colour stands apart from it.",
            choices=tuple(SKIN_TONES),
        ),
        _macro("gender", "0 female … 1 male"),
        _macro("age", f"{ADULT_AGE:g} is 25 years, 1 is 90", minimum=ADULT_AGE),
        _macro("muscle", "0 least … 1 most muscular"),
        _macro("weight", "0 lightest … 1 heaviest build"),
        _macro("height", "0 shortest … 1 tallest (the rig keeps its size: proportions change)"),
        _macro("proportions", "0 uncommon … 1 idealised proportions"),
        Parameter(
            "avatar_file",
            "file",
            "",
            "A humanoid glTF 2.0 or VRM avatar (.glb/.vrm) that films the clip instead of "
            "the built-in signers: its bones are mapped to the engine's and the motion "
            "retargeted onto them, its ARKit morph targets or VRM expressions play the "
            "face. Its SHA-256 is part of the clip's hash.",
        ),
    ),
    source="issue 36",
    order=90,
    apply=_apply,
    check=_check,
    summary=_summary,
)
