"""The animation engine: skeletons, BVH, kinematics, the ASL hand alphabet, timing, rendering.

Pure numpy/scipy code; never imports Django, :mod:`studyplatform`, :mod:`stimuli` or
:mod:`analysis`. Its subpackages, lowest first: ``skeleton`` (joint trees, motions,
files, kinematics), ``rigs`` (the hand and body models), ``fingerspelling`` (alphabet,
word timing, spelling), ``timing`` (the timing models), ``signing`` (sentences),
``avatar`` and ``render`` (meshes and offscreen video), ``techniques`` (what a study
compares, and the one entry point to a clip).
"""

from synthesis.fingerspelling import WordTiming, simple_timing, spell
from synthesis.identity import engine_digest
from synthesis.rigs import BodyModel, HandModel, retarget
from synthesis.skeleton import (
    JOINT_NAME_TABLES,
    BvhError,
    Joint,
    JointMapping,
    Motion,
    Pose,
    Skeleton,
    detect_mapping,
    format_bvh,
    forward_kinematics,
    forward_kinematics_arrays,
    guess_length_unit,
    interpolate_poses,
    monotone_spline_warp,
    parse_bvh,
    piecewise_linear_warp,
    read_bvh,
    resample,
    sample,
    time_warp,
    trim,
    write_bvh,
)
from synthesis.techniques import REGISTRY, ClipError, ClipRequest, build_motion, render_request
from synthesis.timing import constant_timing, normalized_constant_timing

__all__ = [
    "JOINT_NAME_TABLES",
    "REGISTRY",
    "BodyModel",
    "BvhError",
    "ClipError",
    "ClipRequest",
    "HandModel",
    "Joint",
    "JointMapping",
    "Motion",
    "Pose",
    "Skeleton",
    "WordTiming",
    "build_motion",
    "constant_timing",
    "detect_mapping",
    "engine_digest",
    "format_bvh",
    "forward_kinematics",
    "forward_kinematics_arrays",
    "guess_length_unit",
    "interpolate_poses",
    "monotone_spline_warp",
    "normalized_constant_timing",
    "parse_bvh",
    "piecewise_linear_warp",
    "read_bvh",
    "render_request",
    "resample",
    "retarget",
    "sample",
    "simple_timing",
    "spell",
    "time_warp",
    "trim",
    "write_bvh",
]
