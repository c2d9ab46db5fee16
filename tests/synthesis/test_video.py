"""Test MP4 encoding: H.264 yuv420p with faststart, frame counts, determinism, safety."""

import subprocess

import imageio_ffmpeg
import numpy as np
import pytest

from synthesis.render.video import count_frames, write_mp4, write_png


def _frames(n: int = 30, width: int = 64, height: int = 48):
    for k in range(n):
        frame = np.zeros((height, width, 3), dtype=np.uint8)
        frame[..., 0] = (np.arange(width) * 4 + k * 8) % 256
        frame[..., 1] = (np.arange(height)[:, None] * 5) % 256
        yield frame


def _top_level_boxes(path) -> list[str]:
    data = path.read_bytes()
    boxes, offset = [], 0
    while offset + 8 <= len(data):
        size = int.from_bytes(data[offset : offset + 4], "big")
        boxes.append(data[offset + 4 : offset + 8].decode("latin-1"))
        if size < 8:
            break
        offset += size
    return boxes


def test_writes_browser_playable_h264(tmp_path):
    path = tmp_path / "clip.mp4"
    info = write_mp4(_frames(), path, rate_hz=60)
    assert info.n_frames == 30 and (info.width, info.height) == (64, 48)
    assert count_frames(path) == 30
    boxes = _top_level_boxes(path)
    assert boxes.index("moov") < boxes.index("mdat")  # +faststart: playable while loading
    probe = subprocess.run(
        [imageio_ffmpeg.get_ffmpeg_exe(), "-hide_banner", "-i", str(path)],
        capture_output=True,
        text=True,
    )
    assert "Video: h264" in probe.stderr and "yuv420p" in probe.stderr
    assert "60 fps" in probe.stderr


def test_same_frames_give_byte_identical_files(tmp_path):
    write_mp4(_frames(), tmp_path / "a.mp4")
    write_mp4(_frames(), tmp_path / "b.mp4")
    assert (tmp_path / "a.mp4").read_bytes() == (tmp_path / "b.mp4").read_bytes()


def test_progress_is_reported(tmp_path):
    calls = []
    write_mp4(_frames(5), tmp_path / "c.mp4", progress=lambda d, t: calls.append((d, t)), total=5)
    assert calls == [(1, 5), (2, 5), (3, 5), (4, 5), (5, 5)]


def test_bad_frames_leave_no_file_behind(tmp_path):
    path = tmp_path / "bad.mp4"

    def frames():
        yield from _frames(3)
        yield np.zeros((10, 10, 3), dtype=np.uint8)

    with pytest.raises(ValueError, match=r"Frame 3 is \(10, 10\)"):
        write_mp4(frames(), path)
    assert list(tmp_path.iterdir()) == []
    with pytest.raises(ValueError, match="No frames"):
        write_mp4(iter(()), path)


def test_png_poster(tmp_path):
    import imageio.v3 as iio

    frame = next(_frames())
    write_png(frame, tmp_path / "poster.png")
    assert np.array_equal(iio.imread(tmp_path / "poster.png"), frame)
