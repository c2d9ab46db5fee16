"""The default avatars: watertight skins over the hand and body models, skinned by LBS."""

from synthesis.avatar.body_mesh import body_avatar
from synthesis.avatar.hand_mesh import hand_avatar
from synthesis.avatar.model import Avatar, SkinnedPart
from synthesis.avatar.skinning import SkinWeights, linear_blend_skinning, skin_weights

__all__ = [
    "Avatar",
    "SkinWeights",
    "SkinnedPart",
    "body_avatar",
    "hand_avatar",
    "linear_blend_skinning",
    "skin_weights",
]
