"""The animation engine: skeletons, BVH, kinematics, the ASL hand alphabet, timing, rendering.

Pure numpy/scipy code; never imports Django, :mod:`studyplatform`, :mod:`stimuli` or
:mod:`analysis`.
"""

from synthesis.bvh import BvhError, parse_bvh, read_bvh, save_bvh, write_bvh
from synthesis.kinematics import Pose, forward_kinematics, forward_kinematics_arrays
from synthesis.motion import Motion
from synthesis.retime import (
    interpolate_poses,
    monotone_spline_warp,
    piecewise_linear_warp,
    resample,
    sample,
    time_warp,
    trim,
)
from synthesis.skeleton import Joint, Skeleton, guess_length_unit

__all__ = [
    "BvhError",
    "Joint",
    "Motion",
    "Pose",
    "Skeleton",
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
    "save_bvh",
    "time_warp",
    "trim",
    "write_bvh",
]
