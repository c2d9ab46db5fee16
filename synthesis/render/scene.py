"""Cameras and lights of a rendered clip: presets in plain data, no OpenGL here.

Lighting follows seed 003 §4.2: three-point portrait lighting (a key light in front of
the signer, a fill to the side, a rim light behind for the silhouette) plus one extra
fill for the missing ambient. Only the key casts a shadow, and a soft one (the skin
shader's wide penumbra, and a shadow keeps half the key's light): the hard shadow map
left hand-shaped black stains on the chest and laid the hand's shadow over the nose and
mouth during SURPRISE and BROTHER, where the grammar is (issue 52). Without any shadow
MediaPipe read the simple signer's elbow 86 mm off instead of 57: the shading of a hand
over the body is a depth cue worth keeping. A renderer given lights that cast none
skips the shadow pass.
"""

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class Light:
    """One light: a directional key (its direction is from *position_m* to the target) or a
    point light at *position_m*; intensity in pyrender's units (lux / candela)."""

    name: str
    kind: str
    position_m: tuple[float, float, float]
    intensity: float
    color_rgb: tuple[float, float, float] = (1.0, 1.0, 1.0)
    casts_shadow: bool = False


@dataclass(frozen=True)
class CameraPreset:
    """A camera looking from *eye_m* at *target_m*, vertical field of view in degrees."""

    name: str
    eye_m: tuple[float, float, float]
    target_m: tuple[float, float, float]
    yfov_deg: float

    def pose(self) -> np.ndarray:
        """Return the camera-to-world transform (4, 4); the camera looks along its −z."""
        return look_at(np.asarray(self.eye_m), np.asarray(self.target_m))


@dataclass(frozen=True, eq=False)
class CameraPath:
    """A camera that moves: one eye and target per frame, (n_frames, 3) m each, and one
    vertical field of view; frame k is seen as :meth:`at` (k) gives it."""

    name: str
    eye_m: np.ndarray
    target_m: np.ndarray
    yfov_deg: float

    def __post_init__(self) -> None:
        eye, target = np.asarray(self.eye_m, float), np.asarray(self.target_m, float)
        if eye.ndim != 2 or eye.shape[1] != 3 or eye.shape != target.shape:
            raise ValueError(
                f"A camera path needs (n, 3) eyes and targets, not {eye.shape} and {target.shape}."
            )
        object.__setattr__(self, "eye_m", eye)
        object.__setattr__(self, "target_m", target)

    def __len__(self) -> int:
        return len(self.eye_m)

    def at(self, frame: int) -> CameraPreset:
        """Return the camera of one frame."""
        return CameraPreset(
            self.name, tuple(self.eye_m[frame]), tuple(self.target_m[frame]), self.yfov_deg
        )

    def take(self, frames) -> "CameraPath":
        """Return the path of some frames (a slice or indices)."""
        return CameraPath(self.name, self.eye_m[frames], self.target_m[frames], self.yfov_deg)

    def every(self, start: int, step: int) -> "CameraPath":
        """Return the path of frames start, start + step, … (a render worker's share)."""
        return self.take(slice(start, None, step))


def look_at(eye_m: np.ndarray, target_m: np.ndarray, up=(0.0, 1.0, 0.0)) -> np.ndarray:
    """Return the transform (4, 4) of an object at *eye_m* whose −z points at *target_m*."""
    back = eye_m - target_m
    back = back / np.linalg.norm(back)
    right = np.cross(np.asarray(up, dtype=np.float64), back)
    right = right / np.linalg.norm(right)
    true_up = np.cross(back, right)
    pose = np.eye(4)
    pose[:3, 0], pose[:3, 1], pose[:3, 2], pose[:3, 3] = right, true_up, back, eye_m
    return pose


def project_px(camera: CameraPreset, points_m: np.ndarray, width: int, height: int) -> np.ndarray:
    """Return image coordinates (..., 2) in pixels (x right, y down) of world points (..., 3).

    Points behind the camera come out as NaN.
    """
    return project_with_depth(camera, points_m, width, height)[0]


def project_with_depth(
    camera: CameraPreset, points_m: np.ndarray, width: int, height: int
) -> tuple[np.ndarray, np.ndarray]:
    """Return image coordinates (..., 2) in pixels and depths (...) in m along the view of
    world points (..., 3); points behind the camera have NaN coordinates."""
    to_camera = np.linalg.inv(camera.pose())
    points = np.asarray(points_m, dtype=np.float64) @ to_camera[:3, :3].T + to_camera[:3, 3]
    depth = -points[..., 2]
    with np.errstate(divide="ignore", invalid="ignore"):
        focal = 1.0 / np.tan(np.radians(camera.yfov_deg) / 2)
        x_ndc = np.where(depth > 0, points[..., 0] / depth * focal * height / width, np.nan)
        y_ndc = np.where(depth > 0, points[..., 1] / depth * focal, np.nan)
    pixels = np.stack([(x_ndc + 1) / 2 * width, (1 - y_ndc) / 2 * height], axis=-1)
    return pixels, depth


def portrait_lighting(target_m, distance_m: float) -> tuple[Light, ...]:
    """Return key, fill, rim and extra fill placed around *target_m* (seed 003 §4.2).

    The key sits high and to the camera's left at 45°, the fill low at the right, the
    rim behind and above; point-light intensities scale with distance² so that every
    preset is lit alike.
    """
    target = np.asarray(target_m, dtype=np.float64)
    d = distance_m

    def at(x: float, y: float, z: float) -> tuple[float, float, float]:
        return tuple(float(v) for v in target + d * np.array([x, y, z]))

    falloff = d * d
    return (
        Light("key", "directional", at(-0.7, 0.6, 1.0), 0.75, (1.0, 0.96, 0.9), casts_shadow=True),
        Light("fill", "point", at(1.0, 0.1, 0.8), 0.4 * falloff, (0.9, 0.94, 1.0)),
        Light("rim", "point", at(0.3, 0.9, -1.0), 0.8 * falloff),
        Light("extra fill", "point", at(0.0, -0.4, 1.2), 0.22 * falloff),
    )


def hand_close_up(side: str = "right") -> CameraPreset:
    """Return the fingerspelling camera: hand and lower forearm, front on (seed 000 §5.2).

    Frames the hand avatar (forearm root at the origin, wrist 26 cm above it) with room
    for letters that turn the hand (G, H, P, Q) or move it (J, Z, double letters).
    """
    x = 0.08 if side == "right" else -0.08
    return CameraPreset("hand close-up", (x, 0.27, 0.9), (x, 0.25, 0.0), 30.0)


def upper_body_front(side: str = "right") -> CameraPreset:
    """Return the sentence camera: the signer from the hips to above the head, front on.

    *side* names the dominant hand; the view is symmetric, as in signing videos. Placed
    so that, measured on the projected mesh at 640×480 (bench/bench_framing.py), both
    hands stay inside the frame in every frame of the story's sentences, spine on and
    off, and the head is still over 90 px tall (issue 16; the camera 1.7 m away cut a
    raised hand off at the top and a resting one at the bottom).
    """
    del side
    return CameraPreset("upper body", (0.0, 1.40, 2.2), (0.0, 1.38, 0.0), 30.0)


def signing_view(side: str = "right", width: int = 640, height: int = 480) -> CameraPreset:
    """Return the signing view for a frame of *width* × *height*: the upper-body camera
    at 4:3, and at 16:9 or wider the signing space framed from above the head to the
    waist (issue 52), in which the face (brows to chin) is over 130 px tall at 720p and
    no signing hand of a demo sentence leaves the frame (bench/bench_framing.py)."""
    if width / height < WIDE_ASPECT:
        return upper_body_front(side)
    # Farther and narrower than the 4:3 camera: a hand raised in front of the head is
    # magnified less. The frame runs from 1.92 m (the crown is at 1.85 m; LOOKING-BACK's
    # hand over the shoulder reaches 1.91 m) to 0.98 m (the waist, the signing space's
    # lower edge: a hand at rest hangs below it, lowered, synthesis.quality.visibility).
    return CameraPreset("signing view 16:9", (0.0, 1.463, 3.5), (0.0, 1.45, 0.0), 15.4)


WIDE_ASPECT = 1.6


def face_close_up() -> CameraPreset:
    """Return a camera on the face of the upper-body avatar at rest: chin to crown in
    a 640×480 frame, for the face's contact sheet and its MediaPipe test."""
    return CameraPreset("face", (0.0, 1.70, 0.9), (0.0, 1.70, 0.0), 20.0)


CAMERA_PRESETS = {"hand": hand_close_up, "upper-body": upper_body_front}
