"""Read and write the field's ``.pose`` files (pose-format; MediaPipe Holistic layout).

Points are looked up by component and point name, never by index: Holistic files with
576 and 586 points both exist (with and without iris landmarks), and other estimators
lay out other components. Coordinates stay as the file stores them — MediaPipe's image
x and y in pixels of the header's width and height, z in the same units — so
:attr:`PoseRecording.metres_per_unit` says whether a metric scale is known (files this
engine writes) or must be calibrated per signer (captures; see
:mod:`synthesis.capture.handfit`).
"""

import io
from dataclasses import dataclass, replace
from functools import cache
from pathlib import Path

import numpy as np

from synthesis.rigs.hand import HandModel
from synthesis.rigs.landmarks import LANDMARK_NAMES, landmarks

HAND_COMPONENTS = {"right": "RIGHT_HAND_LANDMARKS", "left": "LEFT_HAND_LANDMARKS"}
POSE_COMPONENT = "POSE_LANDMARKS"
# Holistic's metric pose (Holistic's pose_world_landmarks): its depth is the model's
# metric estimate, much surer than the image landmarks' z.
POSE_WORLD_COMPONENT = "POSE_WORLD_LANDMARKS"
# Files this engine writes: one unit is a millimetre, in a 1000 × 1000 "image" whose
# centre holds the palm centre.
EXPORT_SIZE = 1000
EXPORT_METRES_PER_UNIT = 0.001
# MediaPipe's hand connections, for viewers of the files (pairs of point indices).
HAND_LIMBS = (
    (0, 1),
    (1, 2),
    (2, 3),
    (3, 4),
    (0, 5),
    (5, 6),
    (6, 7),
    (7, 8),
    (5, 9),
    (9, 10),
    (10, 11),
    (11, 12),
    (9, 13),
    (13, 14),
    (14, 15),
    (15, 16),
    (13, 17),
    (0, 17),
    (17, 18),
    (18, 19),
    (19, 20),
)


class PoseFileError(ValueError):
    """A .pose file that cannot be read, or lacks what was asked of it."""


def _pose_format():
    try:
        import pose_format
    except ImportError as error:  # pragma: no cover - depends on the install
        raise PoseFileError(
            f"pose-format cannot be imported ({error}); run 'make install' to install it."
        ) from error
    return pose_format


@dataclass(frozen=True)
class PoseRecording:
    """Landmarks over frames: named components of named points, with confidences.

    *points* (n_frames, n_points, 3) as the file stores them; *confidence* (n_frames,
    n_points) in 0…1, 0 where a point was not found; *components* the (name, point
    names) of each component in file order; *width*/*height* the image size the
    coordinates refer to; *metres_per_unit* the metric scale when known, else None.
    """

    fps: float
    components: tuple[tuple[str, tuple[str, ...]], ...]
    points: np.ndarray
    confidence: np.ndarray
    width: int
    height: int
    metres_per_unit: float | None = None

    @property
    def n_frames(self) -> int:
        return len(self.points)

    @property
    def duration_s(self) -> float:
        return self.n_frames / self.fps

    def has_component(self, name: str) -> bool:
        return any(component == name for component, _ in self.components)

    def found_component(self, name: str) -> bool:
        """Return whether *name* is in the file and was found in some frame (a Holistic
        file lays out every component, the ones its writer had no points for unfound)."""
        return self.has_component(name) and bool(np.any(self.component(name)[1] > 0))

    def component(
        self, name: str, point_names: tuple[str, ...] | None = None
    ) -> tuple[np.ndarray, np.ndarray]:
        """Return (points (n_frames, k, 3), confidence (n_frames, k)) of *name*'s points.

        *point_names* picks and orders points (all of the component's by default);
        PoseFileError names a missing component or point.
        """
        offset = 0
        for component, names in self.components:
            if component == name:
                wanted = names if point_names is None else point_names
                missing = [p for p in wanted if p not in names]
                if missing:
                    raise PoseFileError(f"Component {name} has no point(s) {', '.join(missing)}.")
                index = [offset + names.index(p) for p in wanted]
                return self.points[:, index], self.confidence[:, index]
            offset += len(names)
        known = ", ".join(c for c, _ in self.components) or "none"
        raise PoseFileError(f"The file has no component {name} (it has: {known}).")

    def hand(self, side: str = "right") -> tuple[np.ndarray, np.ndarray]:
        """Return one hand's 21 landmarks (n_frames, 21, 3) and confidences, MediaPipe order."""
        if side not in HAND_COMPONENTS:
            raise PoseFileError(f"side must be 'right' or 'left', not {side!r}.")
        return self.component(HAND_COMPONENTS[side], LANDMARK_NAMES)

    def found_hands(self) -> dict[str, float]:
        """Return, per hand component present, the share of frames in which it was found."""
        shares = {}
        for side, name in HAND_COMPONENTS.items():
            if self.has_component(name):
                _, confidence = self.component(name)
                shares[side] = float(np.mean(confidence.max(axis=1) > 0)) if self.n_frames else 0.0
        return shares


def parse_pose(data: bytes, source: str = "<pose>") -> PoseRecording:
    """Return the recording in the bytes of a .pose file (its first person)."""
    pose_format = _pose_format()
    if not isinstance(data, bytes | bytearray) or len(data) < 8:
        raise PoseFileError(f"{source}: not a .pose file (too short).")
    try:
        pose = pose_format.Pose.read(bytes(data))
        body, header = pose.body, pose.header
        raw = np.ma.getdata(body.data).astype(np.float64)
        confidence = np.asarray(body.confidence, dtype=np.float64)
        fps = float(body.fps)
        components = tuple((c.name, tuple(c.points)) for c in header.components)
        width, height = int(header.dimensions.width), int(header.dimensions.height)
    except PoseFileError:
        raise
    except Exception as error:  # the reader raises struct, index and value errors alike
        raise PoseFileError(
            f"{source}: not a readable .pose file ({type(error).__name__}: {error})."
        ) from None
    n_points = sum(len(names) for _, names in components)
    if raw.ndim != 4 or raw.shape[2] != n_points or raw.shape[1] < 1 or raw.shape[3] < 2:
        raise PoseFileError(f"{source}: its data {raw.shape} does not match its header.")
    if not np.isfinite(fps) or fps <= 0:
        raise PoseFileError(f"{source}: its frame rate {fps!r} is not positive.")
    points = np.zeros((raw.shape[0], n_points, 3))
    points[..., : min(raw.shape[3], 3)] = raw[:, 0, :, :3]
    confidence = np.clip(np.nan_to_num(confidence[:, 0]), 0.0, 1.0)
    bad = ~np.isfinite(points).all(axis=-1)
    points[bad], confidence[bad] = 0.0, 0.0
    return PoseRecording(fps, components, points, confidence, width, height)


def read_pose(path: str | Path) -> PoseRecording:
    """Read a .pose file."""
    path = Path(path)
    return parse_pose(path.read_bytes(), str(path))


@cache
def _holistic_components() -> tuple:
    """Return pose-format's MediaPipe Holistic components (names, points, limbs, colours)."""
    _pose_format()
    from pose_format.utils.holistic import holistic_components

    return tuple(holistic_components("XYZC"))


def holistic_layout(recording: PoseRecording) -> PoseRecording:
    """Return *recording* laid out as MediaPipe Holistic: pose-format's components in its
    order, each with all its points; the points *recording* lacks (a face mesh, the legs)
    are there unfound (confidence 0), as Holistic writes what it did not see.

    PoseFileError names a component or point that is not Holistic's.
    """
    layout = tuple((c.name, tuple(c.points)) for c in _holistic_components())
    known = dict(layout)
    for name, names in recording.components:
        if name not in known:
            raise PoseFileError(f"{name} is not a MediaPipe Holistic component.")
        extra = [p for p in names if p not in known[name]]
        if extra:
            raise PoseFileError(f"{name} has no Holistic point(s) {', '.join(extra)}.")
    total = sum(len(names) for _, names in layout)
    points = np.zeros((recording.n_frames, total, 3))
    confidence = np.zeros((recording.n_frames, total))
    offset = 0
    for name, names in layout:
        if recording.has_component(name):
            own = dict(recording.components)[name]
            values, seen = recording.component(name, own)
            at = [offset + names.index(p) for p in own]
            points[:, at], confidence[:, at] = values, seen
        offset += len(names)
    return replace(recording, components=layout, points=points, confidence=confidence)


def format_pose(recording: PoseRecording) -> bytes:
    """Return *recording* as the bytes of a .pose file (one person, XYZC points).

    A recording of Holistic components is written in Holistic's full layout with its
    limbs and colours (:func:`holistic_layout`), so pose-format's tools read it as
    Holistic; any other as it is.
    """
    pose_format = _pose_format()
    from pose_format.numpy.pose_body import NumPyPoseBody
    from pose_format.pose_header import PoseHeader, PoseHeaderComponent, PoseHeaderDimensions

    holistic = {c.name: c for c in _holistic_components()}
    if all(name in holistic for name, _ in recording.components):
        recording = holistic_layout(recording)
    components = []
    for name, names in recording.components:
        if name in holistic:
            components.append(holistic[name])
            continue
        limbs = list(HAND_LIMBS) if name in HAND_COMPONENTS.values() else []
        colors = [(255, 255, 255)] * max(len(limbs), 1)
        components.append(PoseHeaderComponent(name, list(names), limbs, colors, "XYZC"))
    dimensions = PoseHeaderDimensions(recording.width, recording.height, 0)
    header = PoseHeader(0.1, dimensions, components)
    data = recording.points[:, None].astype(np.float32)
    mask = np.repeat((recording.confidence[:, None, :, None] <= 0), 3, axis=-1)
    body = NumPyPoseBody(
        recording.fps,
        np.ma.masked_array(data, mask=mask),
        recording.confidence[:, None].astype(np.float32),
    )
    buffer = io.BytesIO()
    pose_format.Pose(header, body).write(buffer)
    return buffer.getvalue()


def write_pose(recording: PoseRecording, path: str | Path) -> Path:
    """Write *recording* to a .pose file."""
    path = Path(path)
    path.write_bytes(format_pose(recording))
    return path


def from_hand_motion(
    model: HandModel, dofs_rad: np.ndarray, rate_hz: float, side: str | None = None
) -> PoseRecording:
    """Return a hand motion (n_frames, n_dofs) as a .pose recording of its 21 landmarks.

    Units are millimetres (:data:`EXPORT_METRES_PER_UNIT`) in MediaPipe's image axes
    (x right, y down), the palm centre at the middle of a 1000 × 1000 image (a clip's
    export is in its frame's pixels instead: :mod:`synthesis.capture.filmed`).
    """
    side = side or model.side
    marks = np.atleast_3d(landmarks(model, np.atleast_2d(dofs_rad)))
    units = marks / EXPORT_METRES_PER_UNIT + np.array([EXPORT_SIZE / 2, EXPORT_SIZE / 2, 0.0])
    components = ((HAND_COMPONENTS[side], LANDMARK_NAMES),)
    return PoseRecording(
        float(rate_hz),
        components,
        units,
        np.ones(units.shape[:2]),
        EXPORT_SIZE,
        EXPORT_SIZE,
        EXPORT_METRES_PER_UNIT,
    )
