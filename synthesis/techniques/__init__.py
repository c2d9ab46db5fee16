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
from synthesis.techniques.source import (
    ITEM_RECORDING,
    as_checked,
    is_simulated_stand_in,
    retimes_recording,
    takes_item_recording,
    uses_item_recording,
    with_recording,
)

REGISTRY = default_registry()

__all__ = [
    "FIELDS",
    "ITEM_RECORDING",
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
    "as_checked",
    "avatar_and_camera",
    "build_motion",
    "default_registry",
    "filming",
    "is_simulated_stand_in",
    "render_request",
    "retimes_recording",
    "rig_for",
    "takes_item_recording",
    "uses_item_recording",
    "validate_parameters",
    "with_recording",
]
