"""Sentence recordings with their segmentation, and the transitions cut from them.

A :class:`SegmentedRecording` is the body's DOFs over a sentence plus the segmentation
that says where each sign and transition lies (seed 001 §3.2). It comes from a BVH of
the engine's body skeleton or a captured ``.pose`` file (arms fitted as in the
human-motion capture), with its segmentation file beside it (``NAME.segments.json`` or
``NAME.segments.xml``), or from the engine's simulated captures. :func:`cut_transitions`
cuts every sign–transition–sign triple into one :class:`CutTransition` per moving arm.
"""

import json
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from synthesis.transitions.curves import SIDES, arm_columns
from synthesis.transitions.descriptor import DESCRIPTOR_FRAMES
from synthesis.transitions.segments import (
    Segment,
    Segmentation,
    SegmentationError,
    check_segmentation,
    parse_segmentation,
)

SEGMENTATION_SUFFIXES = (".segments.json", ".segments.xml")


class RecordingError(ValueError):
    """A recording that cannot be read or does not fit its segmentation."""


@dataclass(frozen=True, eq=False)
class SegmentedRecording:
    """A sentence recording: body DOFs (n_frames, n_dofs) in radians at *rate_hz*, segmented.

    *simulated* marks the engine's simulated captures (every output built from them
    says so); *signer* names who signed it (for the leave-one-out evaluation's report).
    """

    name: str
    dofs_rad: np.ndarray
    dof_names: tuple[str, ...]
    rate_hz: float
    segmentation: Segmentation
    signer: str = ""
    simulated: bool = False

    def __post_init__(self) -> None:
        dofs = np.asarray(self.dofs_rad, dtype=float)
        if dofs.ndim != 2 or dofs.shape[1] != len(self.dof_names):
            raise RecordingError(
                f"{self.name}: DOFs must be (frames, {len(self.dof_names)}), not {dofs.shape}."
            )
        if not np.all(np.isfinite(dofs)):
            raise RecordingError(f"{self.name}: the recording holds non-finite values.")
        try:
            check_segmentation(self.segmentation, len(dofs))
        except SegmentationError as error:
            raise RecordingError(f"{self.name}: {error}") from None
        object.__setattr__(self, "dofs_rad", dofs)

    def curves(self, side: str) -> np.ndarray:
        """Return *side*'s seven arm curves (n_frames, 7), radians."""
        return self.dofs_rad[:, arm_columns(self.dof_names, side)]


@dataclass(frozen=True, eq=False)
class CutTransition:
    """One arm's recorded transition with the signs around it, cut from a recording.

    *before* (n_b, 7) the first sign's curves, *gap* (n, 7) the transition's frames,
    *after* (n_a, 7) the second sign's; frame 0 of the gap follows before's last frame.
    """

    id: str
    recording: str
    signer: str
    side: str
    order: int
    labels: tuple[str, str]
    rate_hz: float
    before: np.ndarray
    gap: np.ndarray
    after: np.ndarray
    simulated: bool = False
    notes: tuple[str, ...] = field(default=())


def cut_transitions(
    recording: SegmentedRecording,
    min_range_deg: float = 1.0,
    context_frames: int = DESCRIPTOR_FRAMES,
) -> list[CutTransition]:
    """Return every transition of *recording*, once per arm that moves in it.

    An arm moves when one of its curves changes by at least *min_range_deg* from the
    first sign's last frame to the second's first frame or within the gap (a resting arm
    has no transition to learn). Transitions whose signs are shorter than
    *context_frames* (the descriptor's N) are left out.
    """
    found = []
    for side in SIDES:
        curves = recording.curves(side)
        for before, middle, after in recording.segmentation.transitions():
            if before.n_frames < context_frames or after.n_frames < context_frames:
                continue
            cut = _cut(curves, before, middle, after)
            span = np.vstack([cut[0][-1:], cut[1], cut[2][:1]])
            if np.degrees(np.ptp(span, axis=0)).max() < min_range_deg:
                continue
            found.append(
                CutTransition(
                    f"{recording.name}-{middle.order:02d}-{side[0]}",
                    recording.name,
                    recording.signer,
                    side,
                    middle.order,
                    (before.label, after.label),
                    recording.rate_hz,
                    *cut,
                    simulated=recording.simulated,
                )
            )
    return sorted(found, key=lambda t: (t.order, t.side))


def _cut(curves, before: Segment, middle: Segment, after: Segment):
    return (
        curves[before.start_frame : before.end_frame + 1],
        curves[middle.start_frame : middle.end_frame + 1],
        curves[after.start_frame : after.end_frame + 1],
    )


def segmentation_file(path: Path) -> Path | None:
    """Return the segmentation beside recording *path* (``NAME.segments.json|xml``), if any."""
    for suffix in SEGMENTATION_SUFFIXES:
        candidate = path.with_name(path.name.split(".")[0] + suffix)
        if candidate.exists():
            return candidate
    return None


def read_body_dofs(path: str | Path) -> tuple[np.ndarray, tuple[str, ...], float]:
    """Return the body DOFs, their names and the rate of a BVH or .pose recording.

    A BVH must be of the engine's body; its root is reset to the standard position
    (seed 004 §3.2.3). A ``.pose`` file's arms are fitted as ``capture --body`` does,
    hung from shoulders at the standard position. Problems raise :class:`RecordingError`
    naming the file.
    """
    from synthesis.rigs.body import BodyModel

    path = Path(path)
    body = BodyModel("right")
    suffix = path.suffix.lower()
    if suffix == ".bvh":
        from synthesis.skeleton.bvh import BvhError, read_bvh
        from synthesis.skeleton.retime import reset_root

        try:
            motion = reset_root(read_bvh(path))
            dofs = body.dofs_from_motion(motion)
        except (BvhError, ValueError, OSError) as error:
            raise RecordingError(
                f"{path}: {error} A recording is a BVH of the engine's body skeleton or a "
                "captured .pose file."
            ) from None
        return dofs, tuple(body.dof_names), motion.rate_hz
    if suffix == ".pose":
        from synthesis.capture import read_pose
        from synthesis.capture.armfit import fit_arms

        try:
            captured = read_pose(path)
        except (ValueError, OSError) as error:
            raise RecordingError(f"{path}: {error}") from None
        return fit_arms(body, captured).dofs_rad, tuple(body.dof_names), captured.fps
    raise RecordingError(f"{path}: a recording is a .bvh or a .pose file, not {suffix or 'this'}.")


def read_segmentation(path: Path) -> tuple[Segmentation, dict]:
    """Return the one sentence of the segmentation file *path* and its JSON metadata.

    A JSON segmentation may say ``"simulated": true`` and ``"signer"``.
    """
    try:
        text = path.read_text("utf-8")
    except (OSError, UnicodeDecodeError) as error:
        raise RecordingError(f"{path}: cannot be read ({error}).") from None
    try:
        sentences = parse_segmentation(text)
    except SegmentationError as error:
        raise SegmentationError(f"{path}: {error}") from None
    if len(sentences) != 1:
        raise RecordingError(
            f"{path}: a recording's segmentation holds one sentence, not {len(sentences)}."
        )
    return sentences[0], (json.loads(text) if text.lstrip().startswith("{") else {})


def read_recording(path: str | Path, segmentation: str | Path | None = None) -> SegmentedRecording:
    """Return the recording at *path* with its segmentation (found beside it by default).

    Every problem raises :class:`RecordingError` or
    :class:`~synthesis.transitions.segments.SegmentationError` naming the file.
    """
    path = Path(path)
    seg_path = Path(segmentation) if segmentation else segmentation_file(path)
    if seg_path is None:
        raise RecordingError(
            f"{path}: no segmentation beside it (expected "
            f"{path.stem}{SEGMENTATION_SUFFIXES[0]} or …{SEGMENTATION_SUFFIXES[1]})."
        )
    sentence, meta = read_segmentation(seg_path)
    dofs, names, rate_hz = read_body_dofs(path)
    return SegmentedRecording(
        path.name.split(".")[0],
        dofs,
        names,
        rate_hz,
        sentence,
        str(meta.get("signer", "")),
        meta.get("simulated") is True,
    )


def write_recording(recording: SegmentedRecording, directory: str | Path) -> Path:
    """Write *recording* as ``NAME.bvh`` and ``NAME.segments.json`` in *directory*."""
    from synthesis.rigs.body import BodyModel
    from synthesis.skeleton.bvh import write_bvh

    directory = Path(directory)
    directory.mkdir(parents=True, exist_ok=True)
    body = BodyModel("right")
    if tuple(body.dof_names) != recording.dof_names:
        raise RecordingError(f"{recording.name}: only the body rig's motions are written.")
    path = directory / f"{recording.name}.bvh"
    write_bvh(body.as_motion(recording.dofs_rad, recording.rate_hz), path)
    segments = [
        {
            "type": s.kind,
            "order": s.order,
            "start": s.start_frame,
            "end": s.end_frame,
            "label": s.label,
        }
        for s in recording.segmentation.segments
    ]
    data = {
        "simulated": recording.simulated,
        "signer": recording.signer,
        "sentences": [{"number": recording.segmentation.sentence, "segments": segments}],
    }
    (directory / f"{recording.name}.segments.json").write_text(json.dumps(data, indent=1) + "\n")
    return path
