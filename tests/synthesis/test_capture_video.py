"""Test markerless capture: a rendered clip's hand is found, fitted and timed again."""

import json

import imageio.v3 as iio
import numpy as np
import pytest

from synthesis.capture import captured_hand, read_pose
from synthesis.capture.video import CaptureError, capture_hands
from synthesis.cli import main
from synthesis.rigs import HandModel
from synthesis.techniques import ClipRequest, build_motion, render_request

pytestmark = pytest.mark.usefixtures("renderable")
pytest.importorskip(
    "mediapipe.python.solutions.hands",
    reason="CAPTURE TESTS SKIPPED: MediaPipe is not installed (make install adds it)",
)


@pytest.fixture(scope="module")
def clip(tmp_path_factory):
    """Render ABLE in the Constant timing: known DOFs per frame (30 fps, 480×360).

    On the simple avatar's hand, whose figures these are: this tests the capture
    pipeline. MediaPipe reads the human signer's close-up hand worse (on the machine of
    2026-12-05, median finger error 10.9° against 9.5° here; L's hold read as 33 ms of
    243 and E's 630 of 800; bench/bench_capture.py --avatar human: 9.9° over the study
    words against the simple hand's 7.6°), an open point of issue 36.
    """
    request = ClipRequest(
        "word",
        "ABLE",
        {"timing": "constant", "avatar": "simple"},
        rate_hz=30,
        width=480,
        height=360,
    )
    build = build_motion(request)
    path = tmp_path_factory.mktemp("capture") / "able.mp4"
    render_request(request, path, build=build)
    return path, build.motion


def test_a_rendered_hand_is_captured_and_fitted_back(clip):
    path, truth = clip
    recording = capture_hands(path, one_hand="right")
    assert recording.found_hands()["right"] > 0.9
    hand = captured_hand(recording, "right")
    model = HandModel()
    fingers = [
        i
        for i, n in enumerate(model.dof_names)
        if "flexion" in n and not n.startswith(("thumb", "wrist"))
    ]
    n = min(len(truth), len(hand.fit.dofs_rad))
    error_deg = np.degrees(np.abs(hand.fit.dofs_rad[:n, fingers] - truth[:n, fingers]))
    # Measured: median 9.2° (9.5° on the machine of 2026-12-05) on this short clip of
    # two fist letters (A, E), whose occluded fingertips MediaPipe guesses; over the 8
    # study words 7.7° (7.6°), under the 8° target (bench/bench_capture.py
    # --avatar simple).
    assert np.median(error_deg) < 12
    assert hand.quality(recording)["residual_mm_median"] < 15


def test_capture_on_the_command_line_writes_pose_bvh_report_and_timing(clip, tmp_path, capsys):
    path, _ = clip
    pose, bvh, report = tmp_path / "able.pose", tmp_path / "able.bvh", tmp_path / "report"
    assert (
        main(
            [
                "capture",
                str(path),
                "--one-hand",
                "--word",
                "ABLE",
                "--out",
                str(pose),
                "--bvh",
                str(bvh),
                "--report",
                str(report),
            ]
        )
        == 0
    )
    printed = capsys.readouterr().out
    timing = json.loads(printed[printed.index("{") :])
    assert timing["word"] == "ABLE" and len(timing["hold_ms"]) == 4
    # Constant timing: 243 ms holds, the last 800 ms; captured within 150 ms.
    assert np.allclose(timing["hold_ms"], [243, 243, 243, 800], atol=150)
    assert read_pose(pose).n_frames > 60 and bvh.stat().st_size > 0
    _opens_as_holistic_in_pose_format(pose, 480, 360, read_pose(pose).n_frames, body=False)
    quality = json.loads((report / "quality.json").read_text())
    assert quality["hands_found"]["right"] > 0.9 and (report / "quality.png").exists()
    sheet = iio.imread(report / "contact.png")
    assert sheet.shape[0] == 400 and sheet.shape[1] == 8 * 200  # 8 frames, filmed over fitted
    out = tmp_path / "again.mp4"
    assert main(["render-pose-file", str(pose), "--out", str(out), "--size", "96x72"]) == 0
    assert iio.improps(out).shape[0] > 60


def test_bad_videos_are_refused_by_name(tmp_path):
    with pytest.raises(CaptureError, match="no such video file"):
        capture_hands(tmp_path / "missing.mp4")
    text = tmp_path / "notes.txt"
    text.write_text("not a video")
    with pytest.raises(CaptureError, match="not a video"):
        capture_hands(text)
    broken = tmp_path / "broken.mp4"
    broken.write_bytes(b"\x00\x00\x00\x18ftypmp42" + bytes(200))
    with pytest.raises(CaptureError, match=r"not a readable video|reading its frames"):
        capture_hands(broken)
    empty = tmp_path / "empty.mp4"
    iio.imwrite(empty, np.full((10, 64, 64, 3), 90, np.uint8), fps=10, codec="libx264")
    with pytest.raises(CaptureError, match="no hand was found in any of its 10 frames"):
        capture_hands(empty)


def test_a_rendered_signer_is_captured_with_holistic_and_its_arms_fitted(tmp_path):
    """Measured (MY FAVORITE COLOR., 480×360, 10 fps): both hands found in every frame,
    the right elbow 27 mm off (median), with Holistic's metric pose (issue 15); 57 mm
    since issue 36's arm solutions turn the palms as the signs say. At 320×240 the
    anti-aliased hands were lost in a seventh of the frames. The simple avatar, whose
    figures these are: on the human signer the right elbow is 104 mm off (its dark
    sleeve in front of its dark top; issue 36's note)."""
    from synthesis.capture.armfit import fit_arms

    request = ClipRequest.from_parameters(
        "sentence",
        "MY FAVORITE COLOR.",
        {
            "rate_hz": 10.0,
            "spine": False,
            "liveliness": False,
            "width": 480,
            "height": 360,
            "avatar": "simple",
        },
    )
    build = build_motion(request)
    path = tmp_path / "signer.mp4"
    render_request(request, path, build=build)
    pose = tmp_path / "signer.pose"
    assert main(["capture", str(path), "--body", "--out", str(pose)]) == 0
    recording = read_pose(pose)
    assert recording.has_component("POSE_WORLD_LANDMARKS")
    _opens_as_holistic_in_pose_format(pose, 480, 360, len(build.motion))
    fit = fit_arms(build.rig, recording)
    assert fit.found.mean() > 0.9
    # Holistic sees the shoulders, ears and nose: the trunk and head are fitted too.
    assert fit.trunk is not None and fit.trunk.found.mean() > 0.9
    truth, fitted = build.rig.pose(np.asarray(build.motion)), build.rig.pose(fit.dofs_rad)
    elbow = build.rig.skeleton.index("right_elbow")
    miss_mm = np.linalg.norm(fitted.positions_m[:, elbow] - truth.positions_m[:, elbow], axis=1)
    assert np.median(miss_mm) * 1000 < 80


def _opens_as_holistic_in_pose_format(
    path, width: int, height: int, frames: int, body: bool = True
) -> None:
    """Check a capture's .pose with pose-format's own reader (issue 54, item 4): MediaPipe
    Holistic's components in pose-format's order and names, in the video's pixels (the
    nose for a *body*'s capture, the right hand's wrist for a hand's)."""
    pose_format = pytest.importorskip("pose_format")
    from pose_format.utils.generic import detect_known_pose_format
    from pose_format.utils.holistic import holistic_components

    theirs = pose_format.Pose.read(path.read_bytes())
    reference = holistic_components("XYZC")
    assert [c.name for c in theirs.header.components] == [c.name for c in reference]
    for ours, expected in zip(theirs.header.components, reference, strict=True):
        assert list(ours.points) == list(expected.points)
    assert detect_known_pose_format(theirs) == "holistic"
    assert (theirs.header.dimensions.width, theirs.header.dimensions.height) == (width, height)
    hands = theirs.get_components(["POSE_LANDMARKS", "FACE_LANDMARKS", "RIGHT_HAND_LANDMARKS"])
    assert hands.body.data.shape[:3] == (frames, 1, 33 + 468 + 21)
    # In the video's pixels: the point is inside the frame whenever it was seen.
    point = 0 if body else 33 + 468 + 21  # the nose, or the right hand's wrist
    where = theirs.body.data[:, 0, point, :2]
    seen = ~np.ma.getmaskarray(where).any(axis=1) & (theirs.body.confidence[:, 0, point] > 0)
    assert seen.mean() > 0.9
    inside = (where[seen] >= 0).all(axis=1) & (where[seen, 0] < width) & (where[seen, 1] < height)
    assert inside.all()
