"""Export a clip request's motion, the avatar and the camera that filmed it (GLB, BVH)."""

import numpy as np

from synthesis.interchange.glb import avatar_glb


def _built(request, build):
    from synthesis.techniques import build_motion

    return build or build_motion(request)


def request_glb(request, build=None, extras: dict | None = None) -> bytes:
    """Return the GLB of *request*: the avatar that films it, moving as the clip does,
    its face's blendshapes keyed per frame, and the clip's camera (seed 004 §4.2.2's
    skinning, written for any glTF 2.0 player)."""
    from synthesis.techniques.request import film

    build = _built(request, build)
    avatar, camera = film(request, build)
    if isinstance(build.motion, np.ndarray):
        pose = avatar.rig.pose(build.motion)
        weights = None if avatar.drive is None else avatar.drive.weights(build.motion)
    else:  # a recording retargeted onto the skeleton: joint transforms, no face
        pose, weights = build.motion, None
    return avatar_glb(
        avatar,
        pose,
        request.rate_hz,
        weights,
        camera,
        request.width,
        request.height,
        name=f"{request.kind} {request.text}"[:200],
        extras=extras,
    )


def request_bvh(request, build=None) -> str:
    """Return the BVH of *request*'s motion (the rig's joints; no face, no mesh).

    Raise ValueError for a clip whose motion is a recording retargeted onto the
    skeleton rather than the rig's DOFs.
    """
    from synthesis.skeleton.bvh import format_bvh

    build = _built(request, build)
    if not isinstance(build.motion, np.ndarray):
        raise ValueError("This clip's motion is a retargeted recording: export it as GLB.")
    return format_bvh(build.rig.as_motion(build.motion, request.rate_hz))
