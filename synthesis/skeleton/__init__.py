"""Joint trees, motions over frames, BVH files, rotations, forward kinematics and retiming.

The lowest layer of the engine: it imports no other subpackage.
"""

from synthesis.skeleton.bvh import (
    BvhError,
    BvhWarning,
    format_bvh,
    parse_bvh,
    read_bvh,
    write_bvh,
)
from synthesis.skeleton.kinematics import Pose, forward_kinematics, forward_kinematics_arrays
from synthesis.skeleton.mapping import JOINT_NAME_TABLES, JointMapping, detect_mapping
from synthesis.skeleton.motion import Motion
from synthesis.skeleton.retime import (
    interpolate_poses,
    monotone_spline_warp,
    piecewise_linear_warp,
    resample,
    sample,
    time_warp,
    trim,
)
from synthesis.skeleton.skeleton import Joint, Skeleton, guess_length_unit

__all__ = [
    "JOINT_NAME_TABLES",
    "BvhError",
    "BvhWarning",
    "Joint",
    "JointMapping",
    "Motion",
    "Pose",
    "Skeleton",
    "detect_mapping",
    "format_bvh",
    "forward_kinematics",
    "forward_kinematics_arrays",
    "guess_length_unit",
    "interpolate_poses",
    "monotone_spline_warp",
    "parse_bvh",
    "piecewise_linear_warp",
    "read_bvh",
    "resample",
    "sample",
    "time_warp",
    "trim",
    "write_bvh",
]
