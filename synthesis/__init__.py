"""The animation engine: skeletons, BVH, kinematics, the ASL hand alphabet, timing, rendering.

Pure numpy/scipy code; never imports Django, :mod:`studyplatform`, :mod:`stimuli` or
:mod:`analysis`.
"""

from synthesis.body import BodyModel
from synthesis.bvh import BvhError, parse_bvh, read_bvh, save_bvh, write_bvh
from synthesis.hand import HandModel
from synthesis.kinematics import Pose, forward_kinematics, forward_kinematics_arrays
from synthesis.mapping import JOINT_NAME_TABLES, JointMapping, detect_mapping
from synthesis.motion import Motion
from synthesis.retarget import retarget
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
from synthesis.spelling import simple_timing, spell
from synthesis.timing import WordTiming, constant_timing, normalized_constant_timing

__all__ = [
    "JOINT_NAME_TABLES",
    "BodyModel",
    "BvhError",
    "HandModel",
    "Joint",
    "JointMapping",
    "Motion",
    "Pose",
    "Skeleton",
    "WordTiming",
    "constant_timing",
    "detect_mapping",
    "forward_kinematics",
    "forward_kinematics_arrays",
    "guess_length_unit",
    "interpolate_poses",
    "monotone_spline_warp",
    "normalized_constant_timing",
    "parse_bvh",
    "piecewise_linear_warp",
    "read_bvh",
    "resample",
    "retarget",
    "sample",
    "save_bvh",
    "simple_timing",
    "spell",
    "time_warp",
    "trim",
    "write_bvh",
]
