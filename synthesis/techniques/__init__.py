"""Techniques a study compares, as registered plug-ins, and the one way to a clip.

:data:`REGISTRY` holds the item kinds and techniques; :class:`ClipRequest` is an item
under a condition; :func:`build_motion` and :func:`render_request` make its motion and
its clip. See docs/architecture.md, "The technique registry".
"""

from synthesis.techniques.default import default_registry
from synthesis.techniques.parameters import ClipError, Parameter
from synthesis.techniques.registry import (
    MOTION,
    PREPARE,
    ItemKind,
    Registry,
    Technique,
)
from synthesis.techniques.request import (
    FIELDS,
    REQUEST_PARAMETERS,
    Build,
    ClipRequest,
    avatar_and_camera,
    build_motion,
    filming,
    render_request,
    rig_for,
    validate_parameters,
)

REGISTRY = default_registry()

__all__ = [
    "FIELDS",
    "MOTION",
    "PREPARE",
    "REGISTRY",
    "REQUEST_PARAMETERS",
    "Build",
    "ClipError",
    "ClipRequest",
    "ItemKind",
    "Parameter",
    "Registry",
    "Technique",
    "avatar_and_camera",
    "build_motion",
    "default_registry",
    "filming",
    "render_request",
    "rig_for",
    "validate_parameters",
]
