"""Inter-sign transitions (seed 001; spec 04): descriptors, curve fitting into a gap, joins.

The numeric core of the data-driven transitions: the DCT-II descriptor of the frames
around a gap (:mod:`~synthesis.transitions.descriptor`), skewing a stored transition
curve into the gap (:mod:`~synthesis.transitions.skew`, Hermite and B-spline), and
the join-tangent adjustment (:mod:`~synthesis.transitions.joins`). Curves are angles in
radians over frames; the seed's tables are in degrees, converted at the edges. A
sentence recording's segmentation into signs and transitions is read by
:mod:`~synthesis.transitions.segments`; seed 004's concatenation with blending is in
:mod:`~synthesis.transitions.blending`.

Around the core: recordings and the transitions cut from them
(:mod:`~synthesis.transitions.recording`), simulated captures with known segments
(:mod:`~synthesis.transitions.simulate`), the Hermite fit of App. A.1
(:mod:`~synthesis.transitions.hermite_fit`), the database file
(:mod:`~synthesis.transitions.database`), the descriptor search
(:mod:`~synthesis.transitions.search`), fitting a stored transition into a gap
(:mod:`~synthesis.transitions.datadriven`), Table 5.1's evaluation
(:mod:`~synthesis.transitions.evaluate`, :mod:`~synthesis.transitions.report`), and a
sentence's gaps refilled or its signs blended (:mod:`~synthesis.transitions.sentence`).
The command line is ``python -m synthesis.transitions``.
"""

from synthesis.transitions.baselines import (
    hermite_points,
    linear_transition,
    rmse_deg,
    simple_hermite_transition,
)
from synthesis.transitions.blending import blend_offsets, blend_signs, velocity_jumps
from synthesis.transitions.database import (
    DatabaseError,
    StoredCurve,
    TransitionDatabase,
    TransitionEntry,
    build_database,
    fit_curve,
)
from synthesis.transitions.datadriven import MODELS, fit_entry, transition
from synthesis.transitions.descriptor import (
    DESCRIPTOR_COEFFICIENTS,
    DESCRIPTOR_FRAMES,
    dct_ii,
    gap_descriptor,
)
from synthesis.transitions.evaluate import Evaluation, evaluate
from synthesis.transitions.hermite_fit import HermiteCurve, fit_hermite, splice_points
from synthesis.transitions.joins import join_bspline, join_tangent, window_tangent
from synthesis.transitions.recording import (
    CutTransition,
    RecordingError,
    SegmentedRecording,
    cut_transitions,
    read_recording,
    write_recording,
)
from synthesis.transitions.search import DescriptorSearch
from synthesis.transitions.segments import (
    Segment,
    Segmentation,
    SegmentationError,
    check_segmentation,
    parse_segmentation,
)
from synthesis.transitions.simulate import simulated_captures
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
    "MODELS",
    "CutTransition",
    "DatabaseError",
    "DescriptorSearch",
    "Evaluation",
    "HermiteCurve",
    "RecordingError",
    "Segment",
    "Segmentation",
    "SegmentationError",
    "SegmentedRecording",
    "StoredCurve",
    "TransitionDatabase",
    "TransitionEntry",
    "basis_peaks",
    "blend_offsets",
    "blend_signs",
    "build_database",
    "check_segmentation",
    "cut_transitions",
    "dct_ii",
    "evaluate",
    "fit_curve",
    "fit_entry",
    "fit_hermite",
    "gap_descriptor",
    "hermite_points",
    "join_bspline",
    "join_tangent",
    "linear_transition",
    "parse_segmentation",
    "read_recording",
    "rmse_deg",
    "scale_values",
    "simple_hermite_transition",
    "simulated_captures",
    "skew_bspline",
    "skew_tangents",
    "skew_values",
    "splice_points",
    "transition",
    "velocity_jumps",
    "window_tangent",
    "write_recording",
]
