"""The rendered MP4 plays in real headless Chromium (Debian's build, via Playwright)."""

import functools
import http.server
import threading

import pytest

from synthesis.avatar.hand_mesh import hand_avatar
from synthesis.fingerspelling.spelling import spell
from synthesis.render.clip import render_clip
from synthesis.render.scene import hand_close_up
from synthesis.render.video import count_frames

pytestmark = pytest.mark.usefixtures("renderable")


@pytest.fixture
def served(tmp_path):
    """Serve *tmp_path* over HTTP on localhost, as the platform serves stimuli."""
    handler = functools.partial(http.server.SimpleHTTPRequestHandler, directory=str(tmp_path))
    server = http.server.ThreadingHTTPServer(("127.0.0.1", 0), handler)
    thread = threading.Thread(target=server.serve_forever, daemon=True)
    thread.start()
    yield tmp_path, f"http://127.0.0.1:{server.server_address[1]}"
    server.shutdown()
    server.server_close()


def test_rendered_clip_plays_in_chromium(served, page):
    folder, url = served
    motion = spell("OK", rate_hz=60)
    info = render_clip(
        hand_avatar("right"), motion, hand_close_up(), folder / "ok.mp4", width=160, height=120
    )
    assert count_frames(folder / "ok.mp4") == len(motion) == info.n_frames
    (folder / "index.html").write_text(
        '<!doctype html><title>clip</title><link rel="icon" href="data:,">'
        '<video id="v" muted playsinline src="ok.mp4"></video>'
    )
    page.goto(f"{url}/index.html")
    played = page.evaluate(
        """async () => {
            const video = document.getElementById("v");
            if (video.readyState < 1) {
                await new Promise((ok, fail) => {
                    video.onloadedmetadata = ok;
                    video.onerror = () => fail(new Error("video error " + video.error.code));
                });
            }
            await video.play();
            await new Promise((ok) => { video.onended = ok; });
            return {width: video.videoWidth, height: video.videoHeight,
                    duration: video.duration, error: video.error,
                    decoded: video.getVideoPlaybackQuality().totalVideoFrames};
        }"""
    )
    assert played["error"] is None
    assert (played["width"], played["height"]) == (160, 120)
    assert played["duration"] == pytest.approx(len(motion) / 60, abs=0.05)
    assert played["decoded"] > 0
