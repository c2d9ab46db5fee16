"""Offscreen rendering of avatars to PNG stills and H.264 MP4 clips (pyrender, lazily)."""

from synthesis.render.backend import RenderUnavailable, select_platform
from synthesis.render.clip import render_clip, render_still
from synthesis.render.renderer import Renderer
from synthesis.render.scene import (
    CAMERA_PRESETS,
    CameraPreset,
    Light,
    face_close_up,
    hand_close_up,
    portrait_lighting,
    upper_body_front,
)
from synthesis.render.video import VideoInfo, count_frames, write_mp4, write_png

__all__ = [
    "CAMERA_PRESETS",
    "CameraPreset",
    "Light",
    "RenderUnavailable",
    "Renderer",
    "VideoInfo",
    "count_frames",
    "face_close_up",
    "hand_close_up",
    "portrait_lighting",
    "render_clip",
    "render_still",
    "select_platform",
    "upper_body_front",
    "write_mp4",
    "write_png",
]
