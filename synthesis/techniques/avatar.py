"""The signer who films a clip: the human avatar (a body, a skin tone) or the simple one.

Changes no motion: the same DOFs play on either avatar (both are skinned to the
engine's rig), so a study can compare avatars as it compares techniques (issue 36).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from synthesis.avatar.human.build import DEFAULT_SKIN_TONE, SKIN_TONES
from synthesis.avatar.human.phenotype import DEFAULT_PRESET, PRESETS
from synthesis.avatar.looks import AVATARS, Look
from synthesis.techniques.kinds import SIGNED, WORD
from synthesis.techniques.parameters import ClipError, Parameter
from synthesis.techniques.registry import Technique

if TYPE_CHECKING:
    from synthesis.techniques.request import Build


def _look(values) -> Look:
    return Look(values["avatar"], values["body"], values["skin_tone"])


def _apply(build: Build) -> Build:
    return build.but(look=_look(build.request.parameters))


def _check(values) -> None:
    if values["avatar"] == "simple" and (
        values["body"] != DEFAULT_PRESET or values["skin_tone"] != DEFAULT_SKIN_TONE
    ):
        raise ClipError("The simple avatar has one body and skin tone; body and skin_tone "
                        "choose the human avatar's.")  # fmt: skip


def _summary(values) -> str:
    if values["avatar"] == "simple":
        return "simple avatar"
    return f"human signer ({values['body']}, {values['skin_tone']} skin)"


TECHNIQUE = Technique(
    name="avatar",
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
            f"{', '.join(PRESETS)}.",
            choices=tuple(PRESETS),
        ),
        Parameter(
            "skin_tone",
            "choice",
            DEFAULT_SKIN_TONE,
            "The human signer's skin tone; the top's colour stands apart from it.",
            choices=tuple(SKIN_TONES),
        ),
    ),
    source="issue 36",
    order=90,
    apply=_apply,
    check=_check,
    summary=_summary,
)
