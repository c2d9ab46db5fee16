"""Checks of uploaded videos: what decodes is kept, what is cut short is not."""

import subprocess
from pathlib import Path

from studyplatform.files.media_types import decoded_duration_s, remux_webm
from tests.conftest import tiny_webm


def _with_a_repeated_timestamp(source: Path, target: Path) -> None:
    """Copy *source* giving its sixth frame the fifth's timestamp, as a busy Chromium does."""
    import imageio_ffmpeg

    command = [
        imageio_ffmpeg.get_ffmpeg_exe(),
        "-v",
        "error",
        "-y",
        "-i",
        str(source),
        "-c",
        "copy",
        "-bsf:v",
        "setts=ts='if(eq(N,5),PREV_OUTPTS,PTS)'",
        str(target),
    ]
    subprocess.run(command, capture_output=True, check=True)


def test_a_recording_with_two_frames_at_one_millisecond_is_whole(tmp_path):
    """A busy Chromium recorded such a take; the check refused it as "incomplete" (CI)."""
    plain, repeated = tmp_path / "plain.webm", tmp_path / "repeated.webm"
    plain.write_bytes(tiny_webm())
    _with_a_repeated_timestamp(plain, repeated)
    assert decoded_duration_s(repeated) == decoded_duration_s(plain) > 0.9
    assert remux_webm(repeated, tmp_path / "stored.webm")
    assert decoded_duration_s(tmp_path / "stored.webm") > 0.9


def test_a_recording_cut_short_is_not(tmp_path):
    cut = tmp_path / "cut.webm"
    whole = tiny_webm()
    cut.write_bytes(whole[: len(whole) // 3])
    assert decoded_duration_s(cut) is None
