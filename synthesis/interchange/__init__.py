"""Exchange clips with other tools: motion and avatar out as glTF (GLB) and BVH, preview
stills of an imported avatar (reading avatars in: :mod:`synthesis.avatar.imported`)."""

from synthesis.interchange.clip import request_bvh, request_glb
from synthesis.interchange.glb import (
    avatar_glb,
    distinct_weights,
    inverse_bind_matrices,
)

__all__ = [
    "avatar_glb",
    "distinct_weights",
    "inverse_bind_matrices",
    "request_bvh",
    "request_glb",
]
