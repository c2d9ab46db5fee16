"""Export a study clip's motion (and the avatar with it) as participants saw it: GLB, BVH."""

from stimuli.clips import ClipError, ClipSpec
from studyplatform.models import Stimulus

FORMATS = {"glb": "model/gltf-binary", "bvh": "application/octet-stream"}


class NoMotion(ClipError):
    """A clip that has no motion to export (an uploaded video), or a format it lacks."""


def stimulus_motion(stimulus: Stimulus, fmt: str) -> tuple[bytes, str]:
    """Return the clip's motion in *fmt* ("glb" or "bvh") and a file name for it.

    The motion is made again from the clip's recorded specification by this
    installation's engine; the GLB's asset extras name the clip's content hash and both
    engines, so a file from another engine than the clip's says so.
    """
    from synthesis.identity import engine_digest
    from synthesis.interchange import request_bvh, request_glb

    if fmt not in FORMATS:
        raise NoMotion(f"Unknown format {fmt!r}; use glb or bvh.")
    if stimulus.condition.is_uploaded or not stimulus.parameters:
        raise NoMotion("This clip is an uploaded video: it has no motion to export.")
    spec = ClipSpec.from_dict(stimulus.parameters)
    name = f"{stimulus.condition.key}-{stimulus.item.key}-{stimulus.content_hash[:12]}.{fmt}"
    if fmt == "bvh":
        return request_bvh(spec).encode(), name
    extras = {
        "signstudy": {
            "study": stimulus.condition.study.slug,
            "condition": stimulus.condition.key,
            "item": stimulus.item.key,
            "clip": stimulus.content_hash,
            "rendered_by_engine": stimulus.engine_version,
            "exported_by_engine": engine_digest(),
            "parameters": spec.to_dict(),
        }
    }
    return request_glb(spec, extras=extras), name
