"""Markerless capture: find a signer's hands in a video with MediaPipe Hands (on the CPU).

The video's frames are read with imageio-ffmpeg; MediaPipe's Hands solution (its models
ship inside the wheel and run offline; requirements/capture.txt) finds up to two hands
per frame, tracking them from frame to frame. The result is a :class:`PoseRecording` in
the MediaPipe Holistic layout of ``.pose`` files: image x and y in pixels, z in the same
units as x, confidence the detection's handedness score (0 where a hand was not found).

MediaPipe names hands as if the image were mirrored (a selfie view): in an ordinary
camera's view of a signer facing it, the hand it calls "Left" is the signer's right.
*mirrored* says which view the video is.
"""

from collections.abc import Callable
from pathlib import Path

import numpy as np

from synthesis.capture.posefile import (
    HAND_COMPONENTS,
    POSE_COMPONENT,
    POSE_WORLD_COMPONENT,
    PoseRecording,
)
from synthesis.rigs.landmarks import LANDMARK_NAMES

SUFFIXES = (".mp4", ".webm", ".mov", ".m4v", ".mkv", ".avi")
MIN_FRAMES = 2
# Holistic's metric pose (hip-centred, MediaPipe's axes) is stored in millimetres.
WORLD_UNITS_PER_M = 1000.0
# The rate a video without a frame rate of its own is sampled at (frames per second).
UNTIMED_FPS = 30.0


class CaptureError(ValueError):
    """A video that cannot be captured: unreadable, too short, or without hands."""


def _solution(name: str):
    try:
        from mediapipe.python import solutions
    except ImportError as error:  # pragma: no cover - depends on the install
        raise CaptureError(
            f"MediaPipe cannot be imported ({error}); run 'make install' to install it "
            "(requirements/capture.txt)."
        ) from error
    return getattr(solutions, name)


def _hands_solution():
    return _solution("hands")


def _metadata(path: Path) -> dict:
    """Return the video's metadata (ffmpeg's), or raise CaptureError naming the problem."""
    import imageio.v3 as iio

    if not path.is_file():
        raise CaptureError(f"{path}: no such video file.")
    if path.suffix.lower() not in SUFFIXES:
        raise CaptureError(f"{path}: not a video ({', '.join(SUFFIXES)}).")
    try:
        return iio.immeta(path)
    except Exception as error:  # ffmpeg's errors come in many types
        raise CaptureError(f"{path}: not a readable video ({error}).") from None


def read_frames(path: str | Path):
    """Return the video's frame rate and an iterator of its RGB frames (h, w, 3) uint8."""
    import imageio.v3 as iio

    path = Path(path)
    fps = float(_metadata(path).get("fps") or 0)
    # A browser's MediaRecorder writes WebM without a frame rate (frames carry their own
    # times): ffmpeg then samples it at a fixed rate.
    resample = not np.isfinite(fps) or fps <= 0
    if resample:
        fps = UNTIMED_FPS

    def frames():
        import imageio

        try:
            reader = imageio.get_reader(path, "ffmpeg", fps=fps) if resample else iio.imiter(path)
            for frame in reader:
                yield np.ascontiguousarray(frame[..., :3])
        except Exception as error:
            raise CaptureError(f"{path}: reading its frames failed ({error}).") from None

    return fps, frames()


def expected_frames(path: str | Path) -> int | None:
    """Return about how many frames the video has (from its duration), or None if unknown."""
    meta = _metadata(Path(path))
    fps, duration_s = float(meta.get("fps") or 0), float(meta.get("duration") or 0)
    known = np.isfinite(duration_s * fps) and duration_s > 0 and fps > 0
    return round(duration_s * fps) if known else None


def _hands_seen(found, width: int, height: int, one_hand: str | None, sides: dict) -> dict:
    """Return one frame's hands by the signer's side: landmarks in pixels and the score,
    the surer of two that claim one side."""
    seen = {}
    for marks, handed in zip(
        found.multi_hand_landmarks or (), found.multi_handedness or (), strict=True
    ):
        label = handed.classification[0]
        side = one_hand or sides.get(label.label)
        if side is None or (side in seen and seen[side][1] >= label.score):
            continue
        xyz = np.array([(m.x * width, m.y * height, m.z * width) for m in marks.landmark])
        seen[side] = (xyz, float(label.score))
    return seen


def capture_hands(
    path: str | Path,
    mirrored: bool = False,
    progress: Callable[[int], None] | None = None,
    model_complexity: int = 1,
    one_hand: str | None = None,
) -> PoseRecording:
    """Return the hands MediaPipe finds in the video at *path*, frame by frame.

    *one_hand* ("right" or "left") says the video shows only that hand (a close-up):
    MediaPipe then looks for one hand and it is that one, whatever handedness it
    guesses. *progress* receives the number of frames done. Raise CaptureError for an
    unreadable file, a video shorter than two frames, or one in which no hand is found.
    """
    if one_hand not in (None, "right", "left"):
        raise CaptureError(f"one_hand must be 'right', 'left' or None, not {one_hand!r}.")
    hands = _hands_solution()
    fps, frames = read_frames(path)
    sides = {"Left": "left", "Right": "right"} if mirrored else {"Left": "right", "Right": "left"}
    points: dict[str, list] = {"right": [], "left": []}
    scores: dict[str, list] = {"right": [], "left": []}
    width = height = 0
    tracker = hands.Hands(
        static_image_mode=False,
        max_num_hands=1 if one_hand else 2,
        model_complexity=model_complexity,
        min_detection_confidence=0.3,
        min_tracking_confidence=0.3,
    )
    with tracker:
        for number, frame in enumerate(frames, start=1):
            height, width = frame.shape[:2]
            seen = _hands_seen(tracker.process(frame), width, height, one_hand, sides)
            for side in ("right", "left"):
                xyz, score = seen.get(side, (np.zeros((21, 3)), 0.0))
                points[side].append(xyz)
                scores[side].append(np.full(21, score))
            if progress is not None:
                progress(number)
    n = len(points["right"])
    if n < MIN_FRAMES:
        raise CaptureError(f"{path}: the video is too short ({n} frame(s)).")
    if not any(np.max(scores[side]) > 0 for side in scores):
        raise CaptureError(f"{path}: no hand was found in any of its {n} frames.")
    components = tuple((HAND_COMPONENTS[side], LANDMARK_NAMES) for side in ("left", "right"))
    data = np.concatenate([np.array(points["left"]), np.array(points["right"])], axis=1)
    confidence = np.concatenate([np.array(scores["left"]), np.array(scores["right"])], axis=1)
    return PoseRecording(fps, components, data, confidence, width, height)


def _add_holistic_frame(rows: dict, found, width: int, height: int, n_points: int) -> None:
    """Append one frame's Holistic landmarks to *rows* (zeros, unseen, where it found none):
    the pose in pixels, its metric twin, and each hand."""
    scale = np.array([width, height, width])
    if found.pose_landmarks is not None:
        marks = found.pose_landmarks.landmark
        rows["pose"].append(np.array([(m.x, m.y, m.z) for m in marks]) * scale)
        rows["pose_seen"].append(np.array([m.visibility for m in marks]))
        metric = found.pose_world_landmarks.landmark
        rows["world"].append(np.array([(m.x, m.y, m.z) for m in metric]) * WORLD_UNITS_PER_M)
    else:
        rows["pose"].append(np.zeros((n_points, 3)))
        rows["pose_seen"].append(np.zeros(n_points))
        rows["world"].append(np.zeros((n_points, 3)))
    for side in ("left", "right"):
        marks = getattr(found, f"{side}_hand_landmarks")
        seen = marks is not None
        xyz = (
            np.array([(m.x, m.y, m.z) for m in marks.landmark]) * scale
            if seen
            else np.zeros((21, 3))
        )
        rows[side].append(xyz)
        rows[f"{side}_seen"].append(np.full(21, 1.0 if seen else 0.0))


def capture_body(
    path: str | Path, progress: Callable[[int], None] | None = None, model_complexity: int = 1
) -> PoseRecording:
    """Return the body and hands MediaPipe Holistic finds in the video, frame by frame.

    The POSE_LANDMARKS component holds Holistic's 33 pose points in the image
    (confidence: their visibility), POSE_WORLD_LANDMARKS the same points in metric
    space (millimetres, hip-centred); the hand components as :func:`capture_hands`
    writes them. Holistic
    names the signer's own left and right. Raise CaptureError for an unreadable file, a
    video shorter than two frames, or one in which no body is found.
    """
    holistic = _solution("holistic")
    names = tuple(landmark.name for landmark in holistic.PoseLandmark)
    fps, frames = read_frames(path)
    rows = {
        "pose": [],
        "pose_seen": [],
        "world": [],
        "left": [],
        "right": [],
        "left_seen": [],
        "right_seen": [],
    }
    width = height = 0
    with holistic.Holistic(
        static_image_mode=False,
        model_complexity=model_complexity,
        min_detection_confidence=0.3,
        min_tracking_confidence=0.3,
    ) as tracker:
        for number, frame in enumerate(frames, start=1):
            height, width = frame.shape[:2]
            _add_holistic_frame(rows, tracker.process(frame), width, height, len(names))
            if progress is not None:
                progress(number)
    pose, pose_seen, world = rows["pose"], rows["pose_seen"], rows["world"]
    hands = {side: rows[side] for side in ("left", "right")}
    hands_seen = {side: rows[f"{side}_seen"] for side in ("left", "right")}
    n = len(pose)
    if n < MIN_FRAMES:
        raise CaptureError(f"{path}: the video is too short ({n} frame(s)).")
    if not np.max(pose_seen) > 0:
        raise CaptureError(f"{path}: no body was found in any of its {n} frames.")
    components = (
        (POSE_COMPONENT, names),
        (POSE_WORLD_COMPONENT, names),
        (HAND_COMPONENTS["left"], LANDMARK_NAMES),
        (HAND_COMPONENTS["right"], LANDMARK_NAMES),
    )
    data = np.concatenate(
        [np.array(pose), np.array(world), np.array(hands["left"]), np.array(hands["right"])], axis=1
    )
    confidence = np.concatenate(
        [
            np.array(pose_seen),
            np.array(pose_seen),
            np.array(hands_seen["left"]),
            np.array(hands_seen["right"]),
        ],
        axis=1,
    )
    return PoseRecording(fps, components, data, confidence, width, height)
