"""Render stills and clips of an avatar to PNG and MP4 files."""

from pathlib import Path

import numpy as np

from synthesis.avatar.model import Avatar
from synthesis.render.parallel import render_frames
from synthesis.render.renderer import Progress, Renderer
from synthesis.render.scene import CameraPath, CameraPreset
from synthesis.render.video import VideoInfo, write_mp4, write_png
from synthesis.skeleton.kinematics import Pose


def render_still(
    avatar: Avatar,
    dofs_rad: np.ndarray,
    camera: CameraPreset | CameraPath,
    out: str | Path,
    width: int = 640,
    height: int = 480,
) -> Path:
    """Render one pose to a PNG file (through a path's first camera, if given a path)."""
    if isinstance(camera, CameraPath):
        camera = camera.at(0)
    with Renderer(avatar, camera, width, height) as renderer:
        return write_png(renderer.frame(dofs_rad), out)


def render_clip(
    avatar: Avatar,
    motion: np.ndarray | Pose,
    camera: CameraPreset | CameraPath,
    out: str | Path,
    rate_hz: float = 60.0,
    poster: str | Path | None = None,
    poster_frame: int = 0,
    width: int = 640,
    height: int = 480,
    progress: Progress | None = None,
    workers: int = 1,
) -> VideoInfo:
    """Render a motion to an H.264 MP4, and a poster PNG if asked.

    *motion* is DOF vectors (n_frames, n_dofs) or a Pose of the avatar's skeleton;
    *camera* one camera or a path with a camera per frame;
    *progress* receives (frames done, total) as frames are rendered and encoded;
    *workers* > 1 renders in that many processes (see :mod:`synthesis.render.parallel`).
    """
    if not isinstance(motion, Pose):
        motion = np.atleast_2d(motion)
    total = motion.quaternions.shape[0] if isinstance(motion, Pose) else len(motion)
    if not 0 <= poster_frame < total:
        raise ValueError(f"poster_frame must lie in 0…{total - 1}.")
    kept = {}

    def frames():
        rendered = render_frames(avatar, camera, motion, width, height, workers)
        for number, frame in enumerate(rendered):
            if number == poster_frame:
                kept["poster"] = frame
            yield frame

    info = write_mp4(frames(), out, rate_hz, progress=progress, total=total)
    if poster is not None:
        write_png(kept["poster"], poster)
    return info
