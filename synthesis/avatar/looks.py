"""Which avatar films a clip: the human signer (a body and skin tone) or the simple one.

The human signer is MakeHuman's CC0 body on the engine's rig
(:mod:`synthesis.avatar.human`); the simple one is the engine's first avatar, meshed
from round cones (:mod:`synthesis.avatar.body_mesh`, :mod:`~synthesis.avatar.hand_mesh`),
kept for studies made with it. Either has a hand-and-forearm avatar for the close-up and
an upper body for the signing view.
"""

from dataclasses import dataclass, replace

from synthesis.avatar.human.build import DEFAULT_SKIN_TONE, SKIN_TONES
from synthesis.avatar.human.phenotype import (
    ADULT_AGE,
    CUSTOM,
    DEFAULT_PRESET,
    PRESETS,
    RAW_VALUES,
    Phenotype,
)

AVATARS = ("human", "simple")


@dataclass(frozen=True)
class Look:
    """An avatar by name; the human one's body (a preset, or ``custom`` with its macro
    values in *raw*, name → 0–1) and skin tone."""

    avatar: str = "human"
    body: str = DEFAULT_PRESET
    skin_tone: str = DEFAULT_SKIN_TONE
    raw: tuple[tuple[str, float], ...] = ()
    file: str = ""  # a glTF or VRM avatar that films the clip instead (issue 37)

    def __post_init__(self) -> None:
        if self.avatar not in AVATARS:
            raise ValueError(f"Unknown avatar {self.avatar!r}: use {' or '.join(AVATARS)}.")
        if self.body not in PRESETS and self.body != CUSTOM:
            raise ValueError(
                f"Unknown body {self.body!r}: the bodies are {', '.join(PRESETS)} and {CUSTOM}."
            )
        if self.skin_tone not in SKIN_TONES:
            raise ValueError(f"Unknown skin tone {self.skin_tone!r}: {', '.join(SKIN_TONES)}.")
        if self.raw and self.body != CUSTOM:
            raise ValueError(f"Macro values shape a {CUSTOM} body, not the {self.body!r} preset.")
        for name, value in self.raw:
            if name not in RAW_VALUES:
                raise ValueError(f"Unknown macro value {name!r}: {', '.join(RAW_VALUES)}.")
            if name == "age" and value < ADULT_AGE:
                raise ValueError(f"age must be at least {ADULT_AGE} (25 years), not {value}.")

    @property
    def phenotype(self) -> Phenotype:
        """Return the human's body: its preset's, or MakeHuman's default with *raw* set."""
        if self.body == CUSTOM:
            return replace(Phenotype(), **dict(self.raw))
        return PRESETS[self.body]


def avatar_for(view: str, side: str, look: Look = Look()):
    """Return the avatar of *view* ("hand" or "upper-body") for the signer's *side* hand."""
    if look.file:
        from synthesis.avatar.imported.load import imported_avatar

        return imported_avatar(look.file, view, side, avatar_for(view, side, Look()))
    if look.avatar == "simple":
        if view == "hand":
            from synthesis.avatar.hand_mesh import hand_avatar

            return hand_avatar(side)
        from synthesis.avatar.body_mesh import body_avatar

        return body_avatar(side)
    if view == "hand":
        from synthesis.avatar.human.hand import human_hand_avatar

        return human_hand_avatar(side, look.phenotype, look.skin_tone)
    from synthesis.avatar.human.build import human_avatar

    return human_avatar(side, look.phenotype, look.skin_tone)
