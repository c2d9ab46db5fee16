"""The face's channels on the human avatar: ARKit blendshapes driven by the face DOFs.

The engine's face channels (:mod:`synthesis.rigs.face`: brows, lids, gaze, mouth
corners, lips, cheeks, jaw, tongue) are DOFs of the body rig; on the human avatar each
weighs the Face Units pack's ARKit blendshapes (CC0, :mod:`synthesis.avatar.human.assets`)
instead of turning a bone, except gaze, which also turns the eyeballs. :data:`CHANNELS`
gives, per blendshape, the DOFs that raise it: a DOF, the sign of its values that count,
the value (degrees) at which it alone reaches the blendshape's full weight, and its share.
ARKit's "Right" is the face's own right side, the engine's ``right_`` (x < 0).
"""

from types import MappingProxyType

import numpy as np

from synthesis.avatar.skinning import MorphDrive


def _both(shape: str, dof: str, sign: int, full_deg: float, share: float = 1.0) -> dict:
    """Return a sided blendshape pair, each raised by its own side's DOF."""
    return {
        f"{shape}{side.title()}": ((f"{side}_{dof}", sign, full_deg, share),)
        for side in ("right", "left")
    }


def _shared(dof: str, sign: int, full_deg: float, share: float = 0.5) -> tuple:
    """Return a midline blendshape's entries raised by both sides' DOF, half each."""
    return tuple((f"{side}_{dof}", sign, full_deg, share) for side in ("right", "left"))


CHANNELS = MappingProxyType(
    {
        # Brows: the inner brows rise with either side, the outer with their own;
        # a brow drawn down and squeezed toward the nose is ARKit's browDown.
        "browInnerUp": _shared("brow_raise", 1, 4.0),
        **_both("browOuterUp", "brow_raise", 1, 4.0),
        **{
            f"browDown{s.title()}": (
                (f"{s}_brow_raise", -1, 5.0, 1.0),
                (f"{s}_brow_squeeze", 1, 5.0, 0.6),
            )
            for s in ("right", "left")
        },
        # Lids: shut at 48°, wide open at −20°; the lower lid's raise is a squint.
        **_both("eyeBlink", "upper_lid_close", 1, 48.0),
        **_both("eyeWide", "upper_lid_close", -1, 20.0),
        **_both("eyeSquint", "lower_lid_raise", 1, 30.0),
        **_both("cheekSquint", "lower_lid_raise", 1, 30.0, 0.5),
        # The skin round the eyes follows the gaze (the eyeballs turn with their bones).
        **_both("eyeLookDown", "eye_pitch", 1, 30.0),
        **_both("eyeLookUp", "eye_pitch", -1, 25.0),
        **_both("eyeLookIn", "eye_turn", 1, 35.0),
        **_both("eyeLookOut", "eye_turn", -1, 35.0),
        # Mouth corners: out is a stretch, in a pucker; up a smile, down a frown.
        **_both("mouthStretch", "mouth_corner_out", 1, 4.0, 0.7),
        "mouthPucker": _shared("mouth_corner_out", -1, 4.0),
        **_both("mouthSmile", "mouth_corner_up", 1, 4.0, 0.8),
        **_both("mouthFrown", "mouth_corner_up", -1, 3.0),
        "cheekPuff": _shared("cheek_puff", 1, 4.0),
        # Lips pushed out are a funnel, drawn in a roll; the jaw's drop, and the lips
        # pressed shut a little past closed (MM).
        "mouthFunnel": (("upper_lip_forward", 1, 8.0, 0.5), ("lower_lip_forward", 1, 8.0, 0.5)),
        "mouthRollUpper": (("upper_lip_forward", -1, 4.0, 1.0),),
        "mouthRollLower": (("lower_lip_forward", -1, 4.0, 1.0),),
        "jawOpen": (("jaw_open", 1, 12.0, 1.0),),
        **{f"mouthPress{s.title()}": (("jaw_open", -1, 1.0, 0.6),) for s in ("right", "left")},
        "tongueOut": (("tongue_out", 1, 12.0, 1.0),),
    }
)


# Weights past the target a blendshape may reach. The pack's brow raise lifts the brows
# about 1 px at the 640×480 signing view, under the simple avatar's 2 px; the brows carry
# questions (seed 003 §4), so a raise goes 1.6 times as far.
LIMITS = MappingProxyType({"browInnerUp": 1.6, "browOuterUpRight": 1.6, "browOuterUpLeft": 1.6})


def morph_drive(dof_names: list[str]) -> MorphDrive:
    """Return the drive of :data:`CHANNELS` for a rig with these DOFs."""
    names = tuple(CHANNELS)
    rising = np.zeros((len(names), len(dof_names)))
    falling = np.zeros_like(rising)
    for row, entries in enumerate(CHANNELS.values()):
        for dof, sign, full_deg, share in entries:
            matrix = rising if sign > 0 else falling
            matrix[row, dof_names.index(dof)] += share / np.radians(full_deg)
    limits = np.array([LIMITS.get(name, 1.0) for name in names])
    return MorphDrive(names, rising, falling, limits)
