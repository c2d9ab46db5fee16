"""Check the clip a request would render, from its motion alone (nothing is rendered).

The reference is the same item keyed: every technique that shapes the motion between
keys (transitions, spine, hand reduction, liveliness, face) at its default, those that
choose the content (source, timing, signs, avatar) as the clip has them, filmed alike.
The spine's on or off is kept too (``reference_keeps``): off, the arm reaches alone
where the trunk shared the reach, and the demo's S4 left elbow turned 1.9 × as fast
about the shoulder as with the spine on, no faster in the world (issue 52).
"""

import numpy as np

from synthesis.quality.report import ClipQuality, check_motion
from synthesis.skeleton.kinematics import Pose
from synthesis.techniques import REGISTRY, ClipRequest, build_motion
from synthesis.techniques.request import FIELDS, Build, film


def keyed_reference(request: ClipRequest) -> ClipRequest:
    """Return the request of *request*'s item keyed: content kept, motion techniques reset."""
    kept = {
        parameter.name: request.parameters[parameter.name]
        for technique in REGISTRY.for_kind(request.kind)
        for parameter in technique.parameters
        if technique.chooses_content or parameter.name in technique.reference_keeps
    }
    fields = {name: getattr(request, name) for name in FIELDS}
    return ClipRequest(request.kind, request.text, kept, **fields)


def _pose(avatar, build: Build) -> Pose:
    """Return the joint transforms of *build*'s motion on the avatar that films it."""
    motion = build.motion
    return motion if isinstance(motion, Pose) else avatar.rig.pose(np.atleast_2d(motion))


def check_request(request: ClipRequest, build: Build | None = None, filmed=None) -> ClipQuality:
    """Return the checks of the clip *request* renders (*build*: its motion, and *filmed*
    its avatar and camera, if made)."""
    build = build or build_motion(request)
    reference = build_motion(keyed_reference(request))
    avatar, camera = filmed or film(request, build)
    return check_motion(
        avatar,
        camera,
        _pose(avatar, build),
        _pose(avatar, reference),
        request.rate_hz,
        request.width,
        request.height,
        request.side,
    )
