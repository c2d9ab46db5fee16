"""Inter-sign transitions (seed 001; spec 04): descriptors, curve fitting into a gap, joins.

The numeric core of the data-driven transitions: the DCT-II descriptor of the frames
around a gap (:mod:`~synthesis.transitions.descriptor`), skewing a stored transition
curve into the gap (:mod:`~synthesis.transitions.skew`, Hermite and B-spline), and
the join-tangent adjustment (:mod:`~synthesis.transitions.joins`). Curves are angles in
radians over frames; the seed's tables are in degrees, converted at the edges. A
sentence recording's segmentation into signs and transitions is read by
:mod:`~synthesis.transitions.segments`; seed 004's concatenation with blending is in
:mod:`~synthesis.transitions.blending`.
"""

from synthesis.transitions.baselines import (
    hermite_points,
    linear_transition,
    rmse_deg,
    simple_hermite_transition,
)
from synthesis.transitions.blending import blend_offsets, blend_signs, velocity_jumps
from synthesis.transitions.descriptor import (
    DESCRIPTOR_COEFFICIENTS,
    DESCRIPTOR_FRAMES,
    dct_ii,
    gap_descriptor,
)
from synthesis.transitions.joins import join_tangent, window_tangent
from synthesis.transitions.segments import (
    Segment,
    Segmentation,
    SegmentationError,
    check_segmentation,
    parse_segmentation,
)
from synthesis.transitions.skew import (
    basis_peaks,
    scale_values,
    skew_bspline,
    skew_tangents,
    skew_values,
)

__all__ = [
    "DESCRIPTOR_COEFFICIENTS",
    "DESCRIPTOR_FRAMES",
    "Segment",
    "Segmentation",
    "SegmentationError",
    "basis_peaks",
    "blend_offsets",
    "blend_signs",
    "check_segmentation",
    "dct_ii",
    "gap_descriptor",
    "hermite_points",
    "join_tangent",
    "linear_transition",
    "parse_segmentation",
    "rmse_deg",
    "scale_values",
    "simple_hermite_transition",
    "skew_bspline",
    "skew_tangents",
    "skew_values",
    "velocity_jumps",
    "window_tangent",
]
